// SPDX-License-Identifier: MIT
#pragma once
// Exact first entry of a line segment into a capsule, in closed form: the infinite cylinder about the
// axis, clipped to the axis, and the two end spheres (the smallest root of each quadratic). Used by
// rope::bullet::rayTest and by the rope's capsule shape for Bullet's own rayTest and sphere sweeps
// (collision_object/rope_shape.h), so both hit the analytic surface to rounding.

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/capsule.h"

namespace rope::bullet {

// First entry of o + lambda d, lambda in [0, 1], into `capsule`: true with lambda and the axis
// parameter t in [0, 1] of the nearest axis point (0 or 1 on an end sphere). False for a miss, a
// degenerate segment (d = 0), or a segment that starts inside (it never enters).
bool rayCapsule(const btVector3& o, const btVector3& d, const Capsule& capsule, double& lambda, double& t);

}  // namespace rope::bullet
