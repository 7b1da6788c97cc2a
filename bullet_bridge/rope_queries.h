// SPDX-License-Identifier: MIT
#pragma once
// Rope hits of world queries. A rope, dynamic or kinematic, is one Bullet collision object whose shape
// is a compound of its capsules (capsule_proxies.h), so Bullet's own btCollisionWorld::rayTest, convexSweepTest,
// contactTest and contactPairTest report hits on ropes like on any compound, filtered by the rope's
// collisionGroup / collisionMask: ropeHit() below turns such a hit (the object, the child index
// Bullet reports, the hit point) into the rope and the curve parameter s. The functions after it are
// conveniences with exact capsule geometry: Bullet's broadphase finds the ropes, the rope's tree
// the capsules, and a closed-form ray-capsule or the bridge's narrowphase answers.

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <LinearMath/btVector3.h>

#include <optional>
#include <vector>

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/contact.h"

namespace rope::bullet {

class KinematicRope;
class RopeObject;
class RopeWorld;

// A hit on a rope: which rope (a dynamic or a kinematic one), which of its capsules (= the compound
// child index), and the curve parameter s of the point on the capsule's axis nearest to the hit point.
struct RopeHitLocation {
  const RopeObject* rope = nullptr;              // the dynamic rope hit, or nullptr
  const KinematicRope* kinematicRope = nullptr;  // the kinematic rope hit, or nullptr
  int capsule = 0;
  double s = 0.0;
};

// The rope and s of a Bullet query's hit on `object`: childIndex is the compound child Bullet
// reports (LocalRayResult::m_localShapeInfo->m_triangleIndex of a rayTest result,
// LocalConvexResult::m_localShapeInfo->m_triangleIndex of a convexSweepTest result, the index0 /
// index1 argument of ContactResultCallback::addSingleResult), point the hit point (world frame).
// Returns nullopt if object is neither a rope's nor a kinematic rope's. Throws InvalidArgument naming
// "point.x" (.y, .z) for a non-finite point or "childIndex" for an index that names no capsule of the rope.
std::optional<RopeHitLocation> ropeHit(const btCollisionObject& object, int childIndex, const btVector3& point);
// The same for a result that carries no child index (ClosestRayResultCallback, ClosestConvexResultCallback):
// the capsule whose surface is nearest to point.
std::optional<RopeHitLocation> ropeHit(const btCollisionObject& object, const btVector3& point);

struct RayHit {
  const btCollisionObject* body = nullptr;  // the body hit, or nullptr for a rope
  const RopeObject* rope = nullptr;         // the rope hit, or nullptr for a body
  const KinematicRope* kinematicRope = nullptr;  // the kinematic rope hit (in the same Bullet world), or nullptr
  double s = 0.0;                           // rope parameter at the hit (ropes and kinematic ropes)
  double fraction = 1.0;                    // along from -> to, in [0, 1]
  btVector3 point{0, 0, 0};                 // world frame, m
  btVector3 normal{0, 0, 1};                // unit surface normal at the hit
};

// Closest rope surface crossed by the segment from -> to (rays starting inside a rope capsule do not
// hit that capsule): the world's ropes and the kinematic ropes of its Bullet world (KinematicRope),
// exact on the capsules (as Bullet's own rayTest on a rope is: collision_object/rope_shape.h). Throws
// InvalidArgument("from"/"to") for non-finite points.
std::optional<RayHit> rayTestRopes(const RopeWorld& world, const btVector3& from, const btVector3& to);
// Closest hit over the world's bodies (Bullet's closest-hit rayTest) and its ropes.
std::optional<RayHit> rayTest(const RopeWorld& world, const btVector3& from, const btVector3& to);

struct RopeContactHit {
  const RopeObject* rope = nullptr;
  const KinematicRope* kinematicRope = nullptr;  // set instead of rope for a kinematic rope's capsule
  double s = 0.0;   // rope parameter of the contact
  Contact contact;  // as findContacts reports it (normal from the object into the rope)
};

// Every contact between `object` (at its current transform; it need not be in the world) and the
// ropes' capsules, then the kinematic ropes' of the same Bullet world, up to the signed distance
// `margin` (m, >= 0). Throws InvalidArgument("margin"),
// "object.shape" for an object without a shape or one the narrowphase does not support
// (find_contacts.h), or "object.transform.*" for a non-finite transform.
std::vector<RopeContactHit> contactTest(const RopeWorld& world, const btCollisionObject& object, double margin = 0.0);

}  // namespace rope::bullet
