// SPDX-License-Identifier: MIT
#pragma once
// A rope capsule: the segment from `a` to `b` swept by a ball of radius `radius`, in the world frame.
// SI units (metres). The axis may be degenerate (a == b): the capsule is then a sphere.

#include <LinearMath/btVector3.h>

#include <string>

#include "bullet_bridge/bullet_precision.h"

namespace rope::bullet {

struct Capsule {
  btVector3 a{0, 0, 0};  // axis start (parameter t = 0), world frame, m
  btVector3 b{0, 0, 0};  // axis end (parameter t = 1), world frame, m
  btScalar radius = 0;   // m, > 0

  // Point on the axis at parameter t in [0, 1].
  btVector3 axisPoint(btScalar t) const { return a + (b - a) * t; }
};

// Throws rope::InvalidArgument naming `name + ".a"`, `".b"` or `".radius"` unless the endpoints are
// finite and the radius is finite and > 0.
void requireValidCapsule(const std::string& name, const Capsule& capsule);

}  // namespace rope::bullet
