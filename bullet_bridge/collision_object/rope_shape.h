// SPDX-License-Identifier: MIT
#pragma once
// The collision shape of a rope's one Bullet collision object (capsule_proxies.h): a btCompoundShape
// whose children are the rope's capsules over the refined spline segments, so that everything in
// Bullet that understands compounds (btCollisionWorld::rayTest, contactTest, contactPairTest,
// convexSweepTest, the debug drawer) sees the rope, child index = capsule index. The compound's own
// btDbvt is the rope's midphase tree; its leaves are not the capsules' tight boxes but the swept
// capsule boxes of the coming step (CapsuleProxies::updateBoxes), which contain them, so Bullet's
// queries find every capsule and the bridge's midphase finds every pair the step can close. getAabb()
// returns the union of those leaves, grown by the part of the speculative margin the leaves do not
// carry (CapsuleProxies): the broadphase sees one box per rope.
//
// Why the children are not btCapsuleShapes: Bullet's rayTest casts a point at a convex child with its
// subsimplex convex cast, which ends its iteration once the separating vector is below 1 cm (squared
// 1e-4), so its hit lies a few micrometres to 0.4 mm off a 1 cm rope's surface (measured). A concave
// child goes instead through processAllTriangles with Bullet's ray (or convex cast) callback, where
// RopeCapsuleShape answers in closed form (narrowphase/ray_capsule.h): the exact capsule surface,
// normal and fraction, to rounding. Its type is FAST_CONCAVE_MESH_PROXYTYPE, a concave type no shape
// of Bullet's uses (Bullet's extension type CUSTOM_CONCAVE_SHAPE_TYPE is also its
// btSdfCollisionShape's, which its concave algorithm casts to and queries as a distance field). For
// contactTest and contactPairTest, whatever puts rope capsules into a world (a RopeWorld, a
// KinematicRope) installs on its dispatcher an algorithm that hands Bullet a btCapsuleShape of the same
// size in the child's place (capsule_dispatch.h), so those run Bullet's own capsule algorithms. Any
// other triangle callback (Bullet's concave algorithm where that dispatch is not installed: a world
// whose dispatcher is not a btCollisionDispatcher, or a user's table entry registered over ours) gets
// the capsule as a closed triangle mesh, 16 sides round (its facets at most 2 % of the radius inside
// the surface).
// Not API: installed only because capsule_proxies.h holds it; may change in any release.

#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btConcaveShape.h>

#include "bullet_bridge/bullet_precision.h"

namespace rope::bullet {

// One capsule of a rope: a Y-axis capsule (radius, half height of its axis, m) whose half height is
// changed in place as its chord's length changes, and whose index in the rope is its child index.
class RopeCapsuleShape : public btConcaveShape {
 public:
  RopeCapsuleShape(btScalar radius, int index);
  void setHalfHeight(btScalar halfHeight) { halfHeight_ = halfHeight; }
  btScalar radius() const { return radius_; }
  btScalar halfHeight() const { return halfHeight_; }
  int index() const { return index_; }
  // The same capsule as Bullet's own shape, for algorithms that need a convex one.
  btCapsuleShape standIn() const { return btCapsuleShape(radius_, btScalar(2) * halfHeight_); }

  void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;
  // A btTriangleRaycastCallback gets the exact entry point; a btTriangleConvexcastCallback the exact
  // hit of a sphere (any other convex shape: Bullet's continuous convex cast against standIn()); any
  // other callback the triangle mesh.
  void processAllTriangles(btTriangleCallback* callback, const btVector3& aabbMin,
                           const btVector3& aabbMax) const override;
  void calculateLocalInertia(btScalar, btVector3& inertia) const override { inertia.setZero(); }
  // A capsule's size is the rope's: scaling is kept (Bullet's interface asks for it) but not applied.
  void setLocalScaling(const btVector3& scaling) override { scaling_ = scaling; }
  const btVector3& getLocalScaling() const override { return scaling_; }
  const char* getName() const override { return "RopeCapsule"; }

 private:
  btScalar radius_;
  btScalar halfHeight_ = 0;
  int index_;
  btVector3 scaling_{1, 1, 1};
};

class RopeShape : public btCompoundShape {
 public:
  RopeShape() : btCompoundShape(true) {}
  // The box Bullet's broadphase gets (world frame: the rope's object keeps the identity transform).
  void setBox(const btVector3& lo, const btVector3& hi) {
    lo_ = lo;
    hi_ = hi;
  }
  void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override {
    aabbMin = lo_ + t.getOrigin();
    aabbMax = hi_ + t.getOrigin();
  }
  const char* getName() const override { return "RopeShape"; }

 private:
  btVector3 lo_{0, 0, 0}, hi_{0, 0, 0};
};

}  // namespace rope::bullet
