// SPDX-License-Identifier: MIT
#pragma once
// One contact between a rope capsule and a Bullet collision object, in the world frame (metres).
//
// Conventions:
//  * `normal` is a unit vector pointing from the body into the rope: moving the capsule by
//    -distance * normal (distance < 0) separates the two.
//  * `distance` is signed: > 0 is the gap of a speculative contact (the surfaces do not touch yet),
//    < 0 the penetration depth. For a separated pair, pointOnCapsule - pointOnBody = distance*normal.
//  * `t` in [0, 1] is the parameter of the axis point a + t (b - a) nearest to the contact, i.e.
//    where a force on the rope acts along its centre line.

#include <LinearMath/btVector3.h>

#include "bullet_bridge/bullet_precision.h"

namespace rope::bullet {

struct Contact {
  btScalar t = 0;                      // axis parameter, [0, 1]
  btVector3 pointOnCapsule{0, 0, 0};   // on the capsule surface, world frame, m
  btVector3 pointOnBody{0, 0, 0};      // on the body surface, world frame, m
  btVector3 normal{0, 0, 1};           // unit, from the body into the rope
  btScalar distance = 0;               // signed, m: > 0 gap, < 0 penetration
  int childIndex = -1;     // index of the child in the object's top-level btCompoundShape, else -1
  int partIndex = -1;      // mesh part (btStridingMeshInterface subpart) of the triangle, else -1
  int triangleIndex = -1;  // triangle index reported by the concave shape, else -1
};

}  // namespace rope::bullet
