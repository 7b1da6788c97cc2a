// SPDX-License-Identifier: MIT
#pragma once
// Exact distance between a segment and a convex core (convex_support.h): a box in closed form (the
// commonest body), every other core by GJK on their Minkowski difference, with our own simplex
// solver (libccd 2.x has no distance query). For polytope cores (point, segment, hull) GJK terminates
// on the exact closest features; for cylinder and cone cores it converges to a relative accuracy of
// 1e-12 in the distance.

#include <LinearMath/btVector3.h>

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/narrowphase/convex_support.h"

namespace rope::bullet {

struct SegmentConvexDistance {
  enum class Status {
    Separated,     // distance, t and the points are valid (distance may be 0 up to rounding)
    BeyondCutoff,  // the distance is certainly > cutoff; nothing else is set
    Intersecting,  // the segment meets the core; nothing else is set
  };
  Status status = Status::Separated;
  btScalar distance = 0;             // m, >= 0
  btScalar t = 0;                    // segment parameter of pointOnSegment, [0, 1]
  btVector3 pointOnSegment{0, 0, 0};
  btVector3 pointOnCore{0, 0, 0};
};

// Segment p -> q and `core`, both in the core's local frame. `cutoff` (m, >= 0) lets the query stop
// as soon as a separating plane proves the distance exceeds it.
SegmentConvexDistance segmentConvexDistance(const btVector3& p, const btVector3& q,
                                            const ConvexCore& core, btScalar cutoff);

}  // namespace rope::bullet
