// SPDX-License-Identifier: MIT
// The length correction (beyond [B]): it brings the curve's arc length to the target with the leading
// point fixed and every side direction kept, converges like Newton's method (which checks its
// derivative), leaves a curve already at its length bitwise alone, and refuses a correction that would
// collapse a side.
#include "rope/tractrix/length_correction.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <Eigen/Geometry>

#include "rope/spline/arc_length.h"
#include "rope/spline/control_polygon.h"

namespace rope {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A clamped cubic whose polygon turns by turnDegrees (in a plane, then out of it) at each corner.
void bentPolygon(int count, double turnDegrees, KnotVector& knots, PointList& points) {
  knots = KnotVector::clampedUniform(3, count, 0.0, count - 1.0);
  points.clear();
  Vec3 p = Vec3::Zero();
  for (int i = 0; i < count; ++i) {
    points.push_back(p);
    const double heading = i * turnDegrees * kPi / 180.0;
    p += Vec3(std::cos(heading), std::sin(heading) * std::cos(0.1 * i), std::sin(heading) * std::sin(0.1 * i));
  }
}

// Independent of the correction's own quadrature: 24 points on 4 pieces per span.
double fineLength(const KnotVector& knots, const PointList& points) {
  ArcLengthOptions options;
  options.gaussPoints = 24;
  options.piecesPerSpan = 4;
  return arcLength(knots, points, knots.validBegin(), knots.validEnd(), options);
}

TEST(LengthCorrection, RestoresTheLengthKeepingLeaderAndDirections) {
  for (double turn : {10.0, 40.0, 70.0, 100.0}) {
    for (double change : {0.08, 0.01, -0.01, -0.05}) {
      KnotVector knots = KnotVector::clampedUniform(3, 4);
      PointList points;
      bentPolygon(12, turn, knots, points);
      const PointList before = points;
      const double target = (1.0 + change) * fineLength(knots, points);  // lengthen by 8 % .. shorten by 5 %
      const LengthCorrectionResult result = restoreCurveLength(knots, points, target);
      ASSERT_TRUE(result.applied) << turn << " " << change;
      EXPECT_TRUE(result.feasible);
      // Newton converges quadratically: a wrong slope would need many more iterations.
      EXPECT_LE(result.iterations, 5) << turn << " " << change;
      EXPECT_NEAR(result.lengthAfter, target, 1e-12 * target);
      // 8 Gauss points per span against the fine rule (measured: below 2e-10 relative here).
      // The correction is exact in its own rule (settings.lengthGaussPoints, 8 per span); against a
      // fine rule the difference is that rule's quadrature error, which grows with the bend of a span
      // (measured: 3e-13, 7e-11, 9e-9, 9e-7 relative at 10°, 40°, 70°, 100° per corner; subdivision
      // keeps a tractrix rope's corners at or below 40°).
      const double quadrature = turn < 20 ? 1e-12 : turn < 50 ? 2e-10 : turn < 80 ? 2e-8 : 2e-6;
      EXPECT_NEAR(fineLength(knots, points), target, quadrature * target) << turn << " " << change;
      EXPECT_EQ(std::memcmp(points.data(), before.data(), sizeof(Vec3)), 0);  // the leader stays
      for (size_t i = 0; i + 1 < points.size(); ++i) {
        const Vec3 a = before[i + 1] - before[i];
        const Vec3 b = points[i + 1] - points[i];
        EXPECT_LT(a.cross(b).norm(), 1e-12 * a.norm() * b.norm()) << "side " << i;
        EXPECT_GT(a.dot(b), 0.0);
      }
    }
  }
}

TEST(LengthCorrection, PutsTheChangeWhereThePolygonBends) {
  // Straight, then a sharp 90° corner, then straight: the sides at the corner grow the most.
  KnotVector knots = KnotVector::clampedUniform(3, 9, 0.0, 6.0);
  PointList points;
  for (int i = 0; i < 5; ++i) points.push_back(Vec3(-i, 0, 0));
  for (int i = 1; i < 5; ++i) points.push_back(Vec3(-4, i, 0));
  std::vector<double> sides;
  for (size_t i = 0; i + 1 < points.size(); ++i) sides.push_back((points[i + 1] - points[i]).norm());
  const double target = 1.02 * fineLength(knots, points);
  ASSERT_TRUE(restoreCurveLength(knots, points, target).applied);
  std::vector<double> growth;
  for (size_t i = 0; i + 1 < points.size(); ++i) growth.push_back((points[i + 1] - points[i]).norm() / sides[i] - 1.0);
  EXPECT_GT(growth[3], 5 * growth[0]);  // sides 3 and 4 meet at the corner
  EXPECT_GT(growth[4], 5 * growth[7]);
  EXPECT_GT(growth[0], 0.0);            // the even share still lengthens the straight parts
}

TEST(LengthCorrection, LeavesACurveAtItsLengthBitwiseAlone) {
  KnotVector knots = KnotVector::clampedUniform(3, 4);
  PointList points;
  bentPolygon(10, 30.0, knots, points);
  LengthCorrectionOptions options;
  const LengthCorrectionResult first = restoreCurveLength(knots, points, 9.5, options);
  ASSERT_TRUE(first.applied);
  const PointList corrected = points;
  const LengthCorrectionResult second = restoreCurveLength(knots, points, 9.5, options);
  EXPECT_FALSE(second.applied);
  EXPECT_TRUE(second.feasible);
  EXPECT_EQ(second.iterations, 0);
  EXPECT_EQ(std::memcmp(points.data(), corrected.data(), points.size() * sizeof(Vec3)), 0);
}

TEST(LengthCorrection, RefusesToCollapseSidesAndChangesNothing) {
  KnotVector knots = KnotVector::clampedUniform(3, 4);
  PointList points;
  bentPolygon(10, 20.0, knots, points);
  const PointList before = points;
  const double length = fineLength(knots, points);
  // Half the length would need sides shrunk to far less than half of themselves.
  const LengthCorrectionResult result = restoreCurveLength(knots, points, 0.5 * length);
  EXPECT_FALSE(result.applied);
  EXPECT_FALSE(result.feasible);
  EXPECT_EQ(std::memcmp(points.data(), before.data(), points.size() * sizeof(Vec3)), 0);
}

}  // namespace
}  // namespace rope
