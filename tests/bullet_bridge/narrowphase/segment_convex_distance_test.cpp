// SPDX-License-Identifier: MIT
#include "bullet_bridge/narrowphase/segment_convex_distance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <BulletCollision/CollisionShapes/btConvexHullShape.h>

#include "bullet_bridge/narrowphase/segment_triangle_distance.h"
#include "narrowphase_test_support.h"

namespace rope::bullet {
namespace {

using Status = SegmentConvexDistance::Status;
using test::vectorNear;

ConvexCore box(const btVector3& half) {
  ConvexCore core;
  core.kind = ConvexCore::Kind::Box;
  core.halfExtents = half;
  core.size = half.length();
  return core;
}

ConvexCore cylinder(int axis, btScalar radius, btScalar halfHeight) {
  ConvexCore core;
  core.kind = ConvexCore::Kind::Cylinder;
  core.upAxis = axis;
  core.radius = radius;
  core.halfHeight = halfHeight;
  core.size = std::hypot(radius, halfHeight);
  return core;
}

ConvexCore cone(btScalar radius, btScalar halfHeight) {
  ConvexCore core = cylinder(1, radius, halfHeight);
  core.kind = ConvexCore::Kind::Cone;
  return core;
}

constexpr double kBig = 1e9;  // a cutoff that never triggers

TEST(SegmentConvexDistance, BoxFaceEdgeAndCorner) {
  const ConvexCore core = box({1, 0.5, 0.25});
  // Face: parallel to the +y face, 0.3 above it.
  auto r = segmentConvexDistance({-0.5, 0.8, 0}, {0.5, 0.8, 0.1}, core, kBig);
  ASSERT_EQ(r.status, Status::Separated);
  EXPECT_NEAR(r.distance, 0.3, 1e-12);
  EXPECT_NEAR(r.pointOnCore.y(), 0.5, 1e-12);
  // Edge (x = 1, y = 0.5) against a skew segment crossing above it diagonally.
  r = segmentConvexDistance({1.2, 0.7, -1}, {1.2, 0.7, 1}, core, kBig);
  ASSERT_EQ(r.status, Status::Separated);
  EXPECT_NEAR(r.distance, std::sqrt(0.08), 1e-12);
  // The segment is parallel to the edge over z in [-0.25, 0.25]: any t there is a closest point.
  EXPECT_GE(r.t, 0.375 - 1e-12);
  EXPECT_LE(r.t, 0.625 + 1e-12);
  // Corner (1, 0.5, 0.25) against a segment pointing away from it along (1, 1, 1).
  const btVector3 corner(1, 0.5, 0.25), out = btVector3(1, 1, 1).normalized();
  r = segmentConvexDistance(corner + out * 0.2, corner + out * 2, core, kBig);
  ASSERT_EQ(r.status, Status::Separated);
  EXPECT_NEAR(r.distance, 0.2, 1e-12);
  EXPECT_EQ(r.t, 0.0);
  EXPECT_TRUE(vectorNear(r.pointOnCore, corner, 1e-12));
}

TEST(SegmentConvexDistance, IntersectingAndBeyondCutoff) {
  const ConvexCore core = box({1, 1, 1});
  EXPECT_EQ(segmentConvexDistance({-2, 0.5, 0}, {2, 0.5, 0}, core, kBig).status,
            Status::Intersecting);
  EXPECT_EQ(segmentConvexDistance({0, 0, 0}, {0, 0, 0}, core, kBig).status, Status::Intersecting);
  EXPECT_EQ(segmentConvexDistance({-1, 3, 0}, {1, 3, 0}, core, 1.5).status, Status::BeyondCutoff);
  const auto r = segmentConvexDistance({-1, 3, 0}, {1, 3, 0}, core, 2.0);
  ASSERT_EQ(r.status, Status::Separated);
  EXPECT_NEAR(r.distance, 2.0, 1e-12);
}

TEST(SegmentConvexDistance, SegmentCoreIsSegmentSegmentDistance) {
  ConvexCore core;
  core.kind = ConvexCore::Kind::Segment;
  core.upAxis = 2;
  core.halfHeight = 1;
  core.size = 1;
  // Skew: the z-axis segment and an x-direction segment at y = 0.4, z = 0.3.
  auto r = segmentConvexDistance({-1, 0.4, 0.3}, {1, 0.4, 0.3}, core, kBig);
  ASSERT_EQ(r.status, Status::Separated);
  EXPECT_NEAR(r.distance, 0.4, 1e-12);
  EXPECT_NEAR(r.t, 0.5, 1e-12);
  // Parallel, overlapping along z.
  r = segmentConvexDistance({0.6, 0, -0.5}, {0.6, 0, 2}, core, kBig);
  ASSERT_EQ(r.status, Status::Separated);
  EXPECT_NEAR(r.distance, 0.6, 1e-12);
}

TEST(SegmentConvexDistance, CylinderSideCapAndRim) {
  for (int axis = 0; axis < 3; ++axis) {
    const ConvexCore core = cylinder(axis, 0.5, 1);
    const btVector3 up = btVector3(axis == 0, axis == 1, axis == 2);
    const btVector3 side = btVector3(axis == 1, axis == 2, axis == 0);  // a radial direction
    const btVector3 side2 = up.cross(side);
    // Side: segment parallel to the axis, 0.2 outside the mantle.
    auto r = segmentConvexDistance(side * 0.7 - up * 0.5, side * 0.7 + up * 0.5, core, kBig);
    ASSERT_EQ(r.status, Status::Separated);
    EXPECT_NEAR(r.distance, 0.2, 1e-10) << "axis " << axis;
    // Cap: horizontal segment 0.3 above the cap.
    r = segmentConvexDistance(up * 1.3 - side * 0.2, up * 1.3 + side2 * 0.2, core, kBig);
    ASSERT_EQ(r.status, Status::Separated);
    EXPECT_NEAR(r.distance, 0.3, 1e-10) << "axis " << axis;
    // Rim: a point-like segment diagonally off the rim circle, at an oblique radial direction.
    const btVector3 radial = (side * 3 + side2 * 4) / 5;
    const btVector3 rim = radial * 0.5 + up;
    const btVector3 out = (radial + up).normalized();
    r = segmentConvexDistance(rim + out * 0.25, rim + out * 1.5, core, kBig);
    ASSERT_EQ(r.status, Status::Separated);
    EXPECT_NEAR(r.distance, 0.25, 1e-10) << "axis " << axis;
    EXPECT_TRUE(vectorNear(r.pointOnCore, rim, 1e-6)) << "axis " << axis;
  }
}

TEST(SegmentConvexDistance, ConeSlantApexAndBase) {
  const btScalar radius = 0.6, h = 0.4;  // apex (0, 0.4, 0), base circle of radius 0.6 at y = -0.4
  const ConvexCore core = cone(radius, h);
  // Slant: outward normal of the generator in the x-y plane.
  const btVector3 apex(0, h, 0), rim(radius, -h, 0);
  const btVector3 normal = btVector3(2 * h, radius, 0).normalized();
  const btVector3 mid = (apex + rim) / 2;
  auto r = segmentConvexDistance(mid + normal * 0.15, mid + normal * 0.15 + normal.cross({0, 0, 1}) * 0.05,
                                 core, kBig);
  ASSERT_EQ(r.status, Status::Separated);
  EXPECT_NEAR(r.distance, 0.15, 1e-10);
  // Apex: a point straight above it.
  r = segmentConvexDistance({0, 1, 0}, {0, 1.5, 0}, core, kBig);
  ASSERT_EQ(r.status, Status::Separated);
  EXPECT_NEAR(r.distance, 1 - h, 1e-12);
  // Base: a horizontal segment below the base.
  r = segmentConvexDistance({-0.2, -0.9, 0.1}, {0.3, -0.9, -0.1}, core, kBig);
  ASSERT_EQ(r.status, Status::Separated);
  EXPECT_NEAR(r.distance, 0.5, 1e-10);
}

// Point-to-box distance, closed form, for the random cross-check below.
double pointBoxDistance(const btVector3& p, const btVector3& half) {
  btVector3 outside;
  for (int i = 0; i < 3; ++i) outside[i] = std::max(btScalar(0), std::fabs(p[i]) - half[i]);
  return outside.length();
}

TEST(SegmentConvexDistance, BoxMatchesAReferenceMinimisationOnRandomSegments) {
  const btVector3 half(0.7, 0.3, 0.5);
  const ConvexCore core = box(half);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-2, 2);
  int separated = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const btVector3 p(u(rng), u(rng), u(rng)), q(u(rng), u(rng), u(rng));
    auto f = [&](double s) { return pointBoxDistance(p + (q - p) * s, half); };
    double lo = 0, hi = 1;
    for (int i = 0; i < 200; ++i) {
      const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
      if (f(m1) < f(m2)) hi = m2; else lo = m1;
    }
    const double reference = std::min({f(0), f(1), f((lo + hi) / 2)});
    const auto r = segmentConvexDistance(p, q, core, kBig);
    if (reference > 1e-9) {
      ASSERT_EQ(r.status, Status::Separated) << "trial " << trial;
      ASSERT_NEAR(r.distance, reference, 1e-10) << "trial " << trial;
      ASSERT_NEAR(pointBoxDistance(r.pointOnSegment, half), r.distance, 1e-10);
      ++separated;
    } else {
      ASSERT_EQ(r.status, Status::Intersecting) << "trial " << trial;
    }
  }
  EXPECT_GT(separated, 100);
}

// Reference minimum of a convex function of s in [0, 1] by ternary search.
template <typename F>
double minimiseOverSegment(F f) {
  double lo = 0, hi = 1;
  for (int i = 0; i < 200; ++i) {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (f(m1) < f(m2)) hi = m2; else lo = m1;
  }
  return std::min({f(0.0), f(1.0), f((lo + hi) / 2)});
}

TEST(SegmentConvexDistance, CylinderMatchesAReferenceMinimisationOnRandomSegments) {
  // Point-to-cylinder distance in closed form (radial and axial excess), convex along a segment.
  const btScalar radius = 0.4, halfHeight = 0.7;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (int axis = 0; axis < 3; ++axis) {
    const ConvexCore core = cylinder(axis, radius, halfHeight);
    auto pointDistance = [&](const btVector3& x) {
      btVector3 radial = x;
      radial[axis] = 0;
      const double dr = std::max(0.0, double(radial.length()) - radius);
      const double da = std::max(0.0, std::fabs(double(x[axis])) - halfHeight);
      return std::sqrt(dr * dr + da * da);
    };
    int separated = 0;
    for (int trial = 0; trial < 400; ++trial) {
      const btVector3 p(u(rng), u(rng), u(rng)), q(u(rng), u(rng), u(rng));
      const double reference =
          minimiseOverSegment([&](double s) { return pointDistance(p + (q - p) * s); });
      const auto r = segmentConvexDistance(p, q, core, kBig);
      if (reference > 1e-6) {
        ASSERT_EQ(r.status, Status::Separated) << "axis " << axis << " trial " << trial;
        ASSERT_NEAR(r.distance, reference, 1e-9) << "axis " << axis << " trial " << trial;
        ASSERT_NEAR(pointDistance(r.pointOnSegment), r.distance, 1e-9);
        ++separated;
      } else if (reference == 0) {
        ASSERT_EQ(r.status, Status::Intersecting) << "axis " << axis << " trial " << trial;
      }
    }
    EXPECT_GT(separated, 50);
  }
}

TEST(SegmentConvexDistance, SegmentCoreMatchesClosedFormOnRandomSegments) {
  ConvexCore core;
  core.kind = ConvexCore::Kind::Segment;
  core.upAxis = 1;
  core.halfHeight = 0.6;
  core.size = 0.6;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 1000; ++trial) {
    const btVector3 p(u(rng), u(rng), u(rng)), q(u(rng), u(rng), u(rng));
    const btVector3 c0(0, -0.6, 0), c1(0, 0.6, 0);
    btScalar s, t;
    closestSegmentSegment(p, q, c0, c1, s, t);
    const double reference = ((p + (q - p) * s) - (c0 + (c1 - c0) * t)).length();
    const auto r = segmentConvexDistance(p, q, core, kBig);
    if (reference > 1e-9) {
      ASSERT_EQ(r.status, Status::Separated) << "trial " << trial;
      ASSERT_NEAR(r.distance, reference, 1e-12) << "trial " << trial;
    }
  }
}

}  // namespace
}  // namespace rope::bullet

namespace rope::bullet {
namespace {

// The box's closed form against GJK on the same box as a hull of its eight corners (the general path):
// the same status, distance and closest points, on random segments (some degenerate: points).
TEST(SegmentConvexDistance, BoxClosedFormMatchesGjkOnTheSameBoxAsAHull) {
  const btVector3 half(0.7, 0.3, 0.5);
  const ConvexCore boxCore = box(half);
  btConvexHullShape corners;
  for (int i = 0; i < 8; ++i)
    corners.addPoint(btVector3(i & 1 ? half.x() : -half.x(), i & 2 ? half.y() : -half.y(), i & 4 ? half.z() : -half.z()));
  corners.setMargin(0);
  ConvexCore hullCore;
  ASSERT_TRUE(makeConvexCore(corners, hullCore));
  ASSERT_EQ(hullCore.kind, ConvexCore::Kind::Hull);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2, 2);
  int separated = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const btVector3 p(u(rng), u(rng), u(rng));
    const btVector3 q = trial % 4 == 0 ? p : btVector3(u(rng), u(rng), u(rng));
    const auto closed = segmentConvexDistance(p, q, boxCore, kBig);
    const auto gjk = segmentConvexDistance(p, q, hullCore, kBig);
    ASSERT_EQ(closed.status, gjk.status) << "trial " << trial;
    if (closed.status != Status::Separated) continue;
    ++separated;
    ASSERT_NEAR(closed.distance, gjk.distance, 1e-12) << "trial " << trial;
    ASSERT_TRUE(vectorNear(closed.pointOnCore, gjk.pointOnCore, 1e-9)) << "trial " << trial;
    ASSERT_NEAR((closed.pointOnSegment - closed.pointOnCore).length(), closed.distance, 1e-12);
  }
  EXPECT_GT(separated, 1000);
  // The cutoff: a distance beyond it is reported as such.
  EXPECT_EQ(segmentConvexDistance(btVector3(3, 0, 0), btVector3(3, 1, 0), boxCore, 1.0).status, Status::BeyondCutoff);
}

}  // namespace
}  // namespace rope::bullet
