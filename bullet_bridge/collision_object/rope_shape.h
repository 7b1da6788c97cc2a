// SPDX-License-Identifier: MIT
#pragma once
// The collision shape of a rope's one Bullet collision object (capsule_proxies.h): a btCompoundShape
// whose children are the rope's capsules over the refined spline segments, so that everything in
// Bullet that understands compounds (btCollisionWorld::rayTest, contactTest, contactPairTest,
// convexSweepTest, the debug drawer) sees the rope's exact capsule surface, child index = capsule
// index. The compound's own btDbvt is the rope's midphase tree; its leaves are not the capsules'
// tight boxes but the swept capsule boxes of the coming step (CapsuleProxies::updateBoxes), which
// contain them, so Bullet's queries stay exact and the bridge's midphase finds every pair the step
// can close. getAabb() returns the union of those leaves, grown by the part of the speculative margin
// the leaves do not carry (CapsuleProxies): the broadphase sees one box per rope.
// Not API: installed only because capsule_proxies.h holds it; may change in any release.

#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>

#include "bullet_bridge/bullet_precision.h"

namespace rope::bullet {

// A Y-axis capsule whose half height can be changed in place: a capsule child follows its chord's
// length without a new shape (Bullet's btCapsuleShape fixes it at construction).
class RopeCapsuleShape : public btCapsuleShape {
 public:
  explicit RopeCapsuleShape(btScalar radius) : btCapsuleShape(radius, btScalar(0)) {}
  void setHalfHeight(btScalar halfHeight) { m_implicitShapeDimensions[getUpAxis()] = halfHeight; }
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
