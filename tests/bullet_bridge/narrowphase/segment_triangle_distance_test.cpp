// SPDX-License-Identifier: MIT
#include "bullet_bridge/narrowphase/segment_triangle_distance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "narrowphase_test_support.h"

namespace rope::bullet {
namespace {

using test::vectorNear;

btVector3 pointOnTriangle(const btVector3& p, const btVector3& a, const btVector3& b,
                          const btVector3& c) {
  btScalar w[3];
  closestPointOnTriangle(p, a, b, c, w);
  EXPECT_NEAR(w[0] + w[1] + w[2], 1.0, 1e-12);
  EXPECT_GE(w[0], 0.0);
  EXPECT_GE(w[1], 0.0);
  EXPECT_GE(w[2], 0.0);
  return a * w[0] + b * w[1] + c * w[2];
}

const btVector3 kA(0, 0, 0), kB(2, 0, 0), kC(0, 2, 0);

TEST(ClosestPointOnTriangle, FaceEdgeAndVertexRegions) {
  EXPECT_TRUE(vectorNear(pointOnTriangle({0.5, 0.5, 3}, kA, kB, kC), {0.5, 0.5, 0}, 1e-14));
  EXPECT_TRUE(vectorNear(pointOnTriangle({1, -1, 1}, kA, kB, kC), {1, 0, 0}, 1e-14));
  EXPECT_TRUE(vectorNear(pointOnTriangle({-1, 1, -2}, kA, kB, kC), {0, 1, 0}, 1e-14));
  EXPECT_TRUE(vectorNear(pointOnTriangle({2, 2, 0}, kA, kB, kC), {1, 1, 0}, 1e-14));  // edge BC
  EXPECT_TRUE(vectorNear(pointOnTriangle({-1, -1, 5}, kA, kB, kC), kA, 1e-14));
  EXPECT_TRUE(vectorNear(pointOnTriangle({3, -1, 0}, kA, kB, kC), kB, 1e-14));
  EXPECT_TRUE(vectorNear(pointOnTriangle({-1, 3, 1}, kA, kB, kC), kC, 1e-14));
}

TEST(ClosestPointOnTriangle, DegenerateTrianglesFallBackToEdges) {
  // Collinear vertices and a triangle collapsed to a point: no division by zero (traps are on).
  EXPECT_TRUE(vectorNear(pointOnTriangle({1, 1, 0}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}), {1, 0, 0},
                         1e-14));
  EXPECT_TRUE(vectorNear(pointOnTriangle({1, 1, 1}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}), {0, 0, 0},
                         1e-14));
}

TEST(ClosestSegmentSegment, SkewParallelAndDegenerate) {
  btScalar s, t;
  // Skew: x axis segment and a y-direction segment 0.5 above it.
  closestSegmentSegment({-1, 0, 0}, {1, 0, 0}, {0.5, -1, 0.5}, {0.5, 1, 0.5}, s, t);
  EXPECT_NEAR(s, 0.75, 1e-14);
  EXPECT_NEAR(t, 0.5, 1e-14);
  // Clamped: the second segment ends before reaching the first's line.
  closestSegmentSegment({0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {3, 2, 0}, s, t);
  EXPECT_NEAR(s, 1.0, 1e-14);
  EXPECT_NEAR(t, 0.0, 1e-14);
  // Parallel and overlapping: any pair at the minimum distance 1 is correct.
  closestSegmentSegment({0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {3, 1, 0}, s, t);
  const btVector3 gap = (btVector3(2, 0, 0) * s) - (btVector3(1, 1, 0) + btVector3(2, 0, 0) * t);
  EXPECT_NEAR(gap.length(), 1.0, 1e-14);
  // Both degenerate, and one degenerate.
  closestSegmentSegment({0, 0, 0}, {0, 0, 0}, {1, 1, 1}, {1, 1, 1}, s, t);
  EXPECT_EQ(s, 0.0);
  EXPECT_EQ(t, 0.0);
  closestSegmentSegment({0, 0, 0}, {0, 0, 0}, {-1, 1, 0}, {1, 1, 0}, s, t);
  EXPECT_NEAR(t, 0.5, 1e-14);
}

TEST(SegmentTriangleClosest, ParallelAboveTheFace) {
  const auto r = segmentTriangleClosest({0.2, 0.2, 0.7}, {0.8, 0.4, 0.7}, kA, kB, kC);
  EXPECT_NEAR(r.distance, 0.7, 1e-14);
  EXPECT_FALSE(r.crossesPlane);
  EXPECT_NEAR(r.pointOnSegment.z() - r.pointOnTriangle.z(), 0.7, 1e-14);
}

TEST(SegmentTriangleClosest, CrossingTheInterior) {
  const auto r = segmentTriangleClosest({0.5, 0.5, 1}, {0.5, 0.5, -3}, kA, kB, kC);
  EXPECT_EQ(r.distance, 0.0);
  EXPECT_TRUE(r.crossesPlane);
  EXPECT_NEAR(r.s, 0.25, 1e-14);
  EXPECT_TRUE(vectorNear(r.pointOnSegment, {0.5, 0.5, 0}, 1e-14));
}

TEST(SegmentTriangleClosest, SkewToAnEdge) {
  // Segment along z beside edge AB at y = -0.3, x = 1: the closest points are (1, -0.3, 0) on the
  // segment and (1, 0, 0) on the edge.
  const auto r = segmentTriangleClosest({1, -0.3, -1}, {1, -0.3, 1}, kA, kB, kC);
  EXPECT_NEAR(r.distance, 0.3, 1e-14);
  EXPECT_NEAR(r.s, 0.5, 1e-14);
  EXPECT_TRUE(vectorNear(r.pointOnTriangle, {1, 0, 0}, 1e-14));
}

TEST(SegmentTriangleClosest, EndpointAboveTheFacePointingAway) {
  const auto r = segmentTriangleClosest({0.3, 0.4, 0.25}, {0.3, 0.4, 5}, kA, kB, kC);
  EXPECT_NEAR(r.distance, 0.25, 1e-14);
  EXPECT_EQ(r.s, 0.0);
  EXPECT_TRUE(vectorNear(r.pointOnTriangle, {0.3, 0.4, 0}, 1e-14));
}

// Independent reference: the distance from the segment point at s to the triangle is convex in s,
// so a ternary search over s finds the minimum to rounding.
double referenceDistance(const btVector3& p, const btVector3& q, const btVector3& a,
                         const btVector3& b, const btVector3& c) {
  auto f = [&](double s) {
    const btVector3 x = p + (q - p) * s;
    btScalar w[3];
    closestPointOnTriangle(x, a, b, c, w);
    return (x - (a * w[0] + b * w[1] + c * w[2])).length();
  };
  double lo = 0, hi = 1;
  for (int i = 0; i < 200; ++i) {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (f(m1) < f(m2)) hi = m2; else lo = m1;
  }
  return std::min({f(0), f(1), f((lo + hi) / 2)});
}

TEST(SegmentTriangleClosest, MatchesAReferenceMinimisationOnRandomPairs) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  auto point = [&] { return btVector3(u(rng), u(rng), u(rng)); };
  for (int trial = 0; trial < 2000; ++trial) {
    const btVector3 a = point(), b = point(), c = point(), p = point(), q = point();
    const auto r = segmentTriangleClosest(p, q, a, b, c);
    ASSERT_NEAR(r.distance, referenceDistance(p, q, a, b, c), 1e-9) << "trial " << trial;
    ASSERT_NEAR((r.pointOnSegment - r.pointOnTriangle).length(), r.distance, 1e-12);
    ASSERT_TRUE(vectorNear(r.pointOnSegment, p + (q - p) * r.s, 1e-12));
  }
}

}  // namespace
}  // namespace rope::bullet
