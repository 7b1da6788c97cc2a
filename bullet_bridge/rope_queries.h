// SPDX-License-Identifier: MIT
#pragma once
// World queries that see ropes: Bullet's broadphase finds the rope capsules a ray or an object's box
// touches (the capsules are ordinary broadphase proxies), then the exact capsule geometry answers,
// with the rope and the curve parameter s that was hit. Bullet's own btCollisionWorld::rayTest and
// contactTest pass through rope capsules (their shape reports nothing), so these are the calls to use
// when ropes matter; rayTest below also reports the bodies via Bullet's rayTest.

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <LinearMath/btVector3.h>

#include <optional>
#include <vector>

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/contact.h"

namespace rope::bullet {

class RopeObject;
class RopeWorld;

struct RayHit {
  const btCollisionObject* body = nullptr;  // the body hit, or nullptr for a rope
  const RopeObject* rope = nullptr;         // the rope hit, or nullptr for a body
  double s = 0.0;                           // rope parameter at the hit (ropes only)
  double fraction = 1.0;                    // along from -> to, in [0, 1]
  btVector3 point{0, 0, 0};                 // world frame, m
  btVector3 normal{0, 0, 1};                // unit surface normal at the hit
};

// Closest rope surface crossed by the segment from -> to (rays starting inside a rope capsule do not
// hit that capsule). Throws InvalidArgument("from"/"to") for non-finite points.
std::optional<RayHit> rayTestRopes(const RopeWorld& world, const btVector3& from, const btVector3& to);
// Closest hit over the world's bodies (Bullet's closest-hit rayTest) and its ropes.
std::optional<RayHit> rayTest(const RopeWorld& world, const btVector3& from, const btVector3& to);

struct RopeContactHit {
  const RopeObject* rope = nullptr;
  double s = 0.0;   // rope parameter of the contact
  Contact contact;  // as findContacts reports it (normal from the object into the rope)
};

// Every contact between `object` (at its current transform; it need not be in the world) and the
// ropes' capsules, up to the signed distance `margin` (m, >= 0). Throws InvalidArgument("margin"),
// "object.shape" for an object without a shape or one the narrowphase does not support
// (find_contacts.h), or "object.transform.*" for a non-finite transform.
std::vector<RopeContactHit> contactTest(const RopeWorld& world, const btCollisionObject& object, double margin = 0.0);

}  // namespace rope::bullet
