// SPDX-License-Identifier: MIT
#pragma once
// How the friction coefficient of a contact is made from the two surfaces', the Bullet way.
//
// Bullet gives every collision object its own coefficient (btCollisionObject::setFriction, default
// 0.5) and a contact between two of them the product, clamped to 10
// (btManifoldResult::calculateCombinedFriction; a user may replace it through the global
// gCalculateCombinedFrictionCallback). Ropes follow the same rule:
//   rope-body:  mu = BulletRopeSettings::friction * body.getFriction(), clamped to [0, 10];
//   rope-rope:  mu = frictionA * frictionB, clamped to [0, 10] (self-contact: friction^2).
// A rope's default coefficient is 1, so against a default Bullet body (0.5) it gets mu = 0.5, and an
// ice floor (setFriction(0)) or a rubber pad (setFriction(1.5)) changes the rope's friction as it
// changes a box's. RopeWorld::setBodyFrictionCombiner / setRopeFrictionCombiner replace either rule
// (e.g. the minimum, or a table per material pair); a combiner must return a finite value >= 0, else
// that rope's substep is refused like any other failure in it (counted, the rope keeps its state).
//
// Rolling and spinning friction (btCollisionObject::setRollingFriction / setSpinningFriction) are not
// applied to rope contacts: the rope has no rotation about its own axis, so it cannot roll or spin
// against a body, and a body rolling along a rope is resisted by the rope's line contact (its normal
// pressure and Coulomb friction along the touching stretch), not by a rolling-resistance torque.

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>

#include <functional>

namespace rope::bullet {

class RopeObject;

// Bullet's MAX_FRICTION (btManifoldResult.cpp).
constexpr double kMaxCombinedFriction = 10.0;

// a * b clamped to [0, kMaxCombinedFriction] (both finite and >= 0, as validated settings are).
inline double combinedFriction(double a, double b) {
  const double product = a * b;
  return product < kMaxCombinedFriction ? product : kMaxCombinedFriction;
}

// The friction coefficient of a rope-body contact (finite, >= 0).
using BodyFrictionCombiner = std::function<double(const RopeObject& rope, const btCollisionObject& body)>;
// The friction coefficient of a contact between two ropes, or between two parts of one rope (a == b).
using RopeFrictionCombiner = std::function<double(const RopeObject& a, const RopeObject& b)>;

}  // namespace rope::bullet
