// SPDX-License-Identifier: MIT
#pragma once
// Exact closest points between primitives in 3-D: point–triangle, segment–segment and
// segment–triangle. Degenerate input (zero-length segments, collinear triangle vertices) is handled
// without dividing by zero. Metres, any frame.

#include <LinearMath/btVector3.h>

#include "bullet_bridge/bullet_precision.h"

namespace rope::bullet {

// Closest point of triangle (a, b, c) to p, as barycentric weights (wa, wb, wc) >= 0 summing to 1.
void closestPointOnTriangle(const btVector3& p, const btVector3& a, const btVector3& b,
                            const btVector3& c, btScalar weights[3]);

// Closest points p1 + s (q1 - p1) and p2 + t (q2 - p2), s, t in [0, 1], of two segments.
void closestSegmentSegment(const btVector3& p1, const btVector3& q1, const btVector3& p2,
                           const btVector3& q2, btScalar& s, btScalar& t);

struct SegmentTriangleClosest {
  btScalar distance = 0;              // >= 0, m
  btScalar s = 0;                     // segment parameter of pointOnSegment, [0, 1]
  btVector3 pointOnSegment{0, 0, 0};
  btVector3 pointOnTriangle{0, 0, 0};
  bool crossesPlane = false;  // the segment passes through the triangle's interior from one side
                              // of its plane to the other (then distance == 0)
};

// Closest points between segment (p, q) and triangle (a, b, c). The minimum over a disjoint pair
// is attained at a segment endpoint against the triangle or at a triangle edge against the
// segment, so those five candidates plus the crossing test are exact.
SegmentTriangleClosest segmentTriangleClosest(const btVector3& p, const btVector3& q,
                                              const btVector3& a, const btVector3& b,
                                              const btVector3& c);

}  // namespace rope::bullet
