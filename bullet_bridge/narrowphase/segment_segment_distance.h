// SPDX-License-Identifier: MIT
#pragma once
// Closest points of two segments: the narrowphase of rope-rope contact (two capsules touch where
// their axes come closer than the sum of their radii). Exact (clamped closed form); for parallel
// segments, whose closest points are not unique, it returns the middle of the overlapping range, so
// that two ropes lying side by side get their contact at the centre of what they share rather than
// at an end.

#include <LinearMath/btVector3.h>

#include "bullet_bridge/bullet_precision.h"

namespace rope::bullet {

struct SegmentPairClosest {
  double s = 0.0;         // parameter on the first segment, [0, 1]
  double t = 0.0;         // parameter on the second segment, [0, 1]
  double distance = 0.0;  // |p(s) - q(t)|, m
};

// Segments p0 -> p1 and q0 -> q1 (either may be degenerate, a point).
SegmentPairClosest segmentSegmentClosest(const btVector3& p0, const btVector3& p1, const btVector3& q0,
                                         const btVector3& q1);

}  // namespace rope::bullet
