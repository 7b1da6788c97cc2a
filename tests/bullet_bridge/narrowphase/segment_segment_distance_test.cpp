// SPDX-License-Identifier: MIT
#include "bullet_bridge/narrowphase/segment_segment_distance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace rope::bullet {
namespace {

btVector3 pointAt(const btVector3& a, const btVector3& b, double t) { return a + (b - a) * static_cast<btScalar>(t); }

// Brute force on a grid, refined around its best cell: an independent reference.
double referenceDistance(const btVector3& p0, const btVector3& p1, const btVector3& q0, const btVector3& q1) {
  double best = std::numeric_limits<double>::infinity();
  double bs = 0.0, bt = 0.0;
  constexpr int kGrid = 200;
  for (int i = 0; i <= kGrid; ++i)
    for (int j = 0; j <= kGrid; ++j) {
      const double d = static_cast<double>((pointAt(p0, p1, double(i) / kGrid) - pointAt(q0, q1, double(j) / kGrid)).length());
      if (d < best) best = d, bs = double(i) / kGrid, bt = double(j) / kGrid;
    }
  for (int i = -100; i <= 100; ++i)
    for (int j = -100; j <= 100; ++j) {
      const double s = std::clamp(bs + i * 1e-4, 0.0, 1.0), t = std::clamp(bt + j * 1e-4, 0.0, 1.0);
      best = std::min(best, static_cast<double>((pointAt(p0, p1, s) - pointAt(q0, q1, t)).length()));
    }
  return best;
}

TEST(SegmentSegmentClosest, MatchesBruteForceOnRandomSegments) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  const auto point = [&] { return btVector3(btScalar(coordinate(random)), btScalar(coordinate(random)), btScalar(coordinate(random))); };
  for (int trial = 0; trial < 60; ++trial) {
    const btVector3 p0 = point(), p1 = point(), q0 = point(), q1 = point();
    const SegmentPairClosest closest = segmentSegmentClosest(p0, p1, q0, q1);
    ASSERT_GE(closest.s, 0.0);
    ASSERT_LE(closest.s, 1.0);
    ASSERT_GE(closest.t, 0.0);
    ASSERT_LE(closest.t, 1.0);
    // The reported distance is that of the reported points, and no larger than the brute force's.
    EXPECT_NEAR(closest.distance, static_cast<double>((pointAt(p0, p1, closest.s) - pointAt(q0, q1, closest.t)).length()), 1e-6);
    EXPECT_LE(closest.distance, referenceDistance(p0, p1, q0, q1) + 1e-6) << trial;
  }
}

TEST(SegmentSegmentClosest, CrossingSegmentsMeetAtTheirIntersection) {
  const SegmentPairClosest closest =
      segmentSegmentClosest(btVector3(-1, 0, 0), btVector3(1, 0, 0), btVector3(0.5, -1, 0.2), btVector3(0.5, 1, 0.2));
  EXPECT_NEAR(closest.s, 0.75, 1e-12);
  EXPECT_NEAR(closest.t, 0.5, 1e-12);
  EXPECT_NEAR(closest.distance, 0.2, 1e-12);
}

TEST(SegmentSegmentClosest, ParallelSegmentsMeetInTheMiddleOfTheirOverlap) {
  // Side by side over x in [0.5, 1]: the contact is at x = 0.75, not at an end.
  const SegmentPairClosest closest =
      segmentSegmentClosest(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0.5, 0.1, 0), btVector3(1.5, 0.1, 0));
  EXPECT_NEAR(closest.s, 0.75, 1e-12);
  EXPECT_NEAR(closest.t, 0.25, 1e-12);
  EXPECT_NEAR(closest.distance, 0.1, 1e-12);
  // Antiparallel and apart along the line: the nearer ends.
  const SegmentPairClosest apart =
      segmentSegmentClosest(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(3, 0.1, 0), btVector3(2, 0.1, 0));
  EXPECT_NEAR(apart.s, 1.0, 1e-12);
  EXPECT_NEAR(apart.t, 1.0, 1e-12);
  EXPECT_NEAR(apart.distance, std::hypot(1.0, 0.1), 1e-12);
}

TEST(SegmentSegmentClosest, DegenerateSegmentsArePoints) {
  const btVector3 point(0.3, 1, 0);
  const SegmentPairClosest toSegment = segmentSegmentClosest(point, point, btVector3(0, 0, 0), btVector3(1, 0, 0));
  EXPECT_NEAR(toSegment.t, 0.3, 1e-12);
  EXPECT_NEAR(toSegment.distance, 1.0, 1e-12);
  const SegmentPairClosest fromSegment = segmentSegmentClosest(btVector3(0, 0, 0), btVector3(1, 0, 0), point, point);
  EXPECT_NEAR(fromSegment.s, 0.3, 1e-12);
  const SegmentPairClosest points = segmentSegmentClosest(point, point, btVector3(0, 0, 0), btVector3(0, 0, 0));
  EXPECT_NEAR(points.distance, static_cast<double>(point.length()), 1e-12);
}

}  // namespace
}  // namespace rope::bullet
