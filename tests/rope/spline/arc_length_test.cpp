// SPDX-License-Identifier: MIT
#include "rope/spline/arc_length.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "tests/rope/spline/spline_test_support.h"

namespace rope {
namespace {

using test::expectInvalid;

const double kPi = std::acos(-1.0);

Vec3 direction(double angle) { return Vec3(std::cos(angle), std::sin(angle), 0.0); }

// Relative shortfall 1 - L of a single-span piece with sides of length 1 (the straight piece has
// length 1), built as a B-spline on uniform unclamped knots so that the valid range is one span.
double quadraticShortfall(double includedAngleDegrees) {
  const double turn = kPi - includedAngleDegrees * kPi / 180.0;
  const BSplineCurve piece(KnotVector::uniform(2, 3), PointList{Vec3(-1, 0, 0), Vec3::Zero(), direction(turn)});
  return 1.0 - arcLength(piece);
}

// Cubic piece: the included angle at q_2 is theta; at q_1 it is 180 degrees ("other angle 180")
// or theta as well, turning the same way (the planar worst case, docs/method.md §14).
double cubicShortfall(double includedAngleDegrees, bool bothAngles) {
  const double turn = kPi - includedAngleDegrees * kPi / 180.0;
  PointList points{Vec3(-1, 0, 0), Vec3::Zero()};
  if (bothAngles) {
    points.push_back(direction(turn));
    points.push_back(points.back() + direction(2 * turn));
  } else {
    points.push_back(Vec3(1, 0, 0));
    points.push_back(points.back() + direction(turn));
  }
  const BSplineCurve piece(KnotVector::uniform(3, 4), points);
  return 1.0 - arcLength(piece);
}

TEST(ArcLength, ReproducesTheCheckTableOfSpec4) {
  struct Row {
    double angle;
    double quadratic;
    double cubicOtherStraight;
    double cubicBothEqual;
  };
  const Row table[] = {{60, 0.3099, 0.2122, 0.4316},
                       {100, 0.1518, 0.1053, 0.2193},
                       {140, 0.0400, 0.0279, 0.0593},
                       {160, 0.0101, 0.0071, 0.0151}};
  for (const Row& row : table) {
    const double q = quadraticShortfall(row.angle);
    const double c1 = cubicShortfall(row.angle, false);
    const double c2 = cubicShortfall(row.angle, true);
    std::printf("%5.0f deg: quadratic %.5f  cubic(other 180) %.5f  cubic(both) %.5f\n", row.angle, q, c1, c2);
    EXPECT_NEAR(q, row.quadratic, 1e-4) << row.angle;
    EXPECT_NEAR(c1, row.cubicOtherStraight, 1e-4) << row.angle;
    EXPECT_NEAR(c2, row.cubicBothEqual, 1e-4) << row.angle;
  }
}

TEST(ArcLength, StraightPiecesHaveUnitLength) {
  EXPECT_NEAR(quadraticShortfall(180.0), 0.0, 1e-14);
  EXPECT_NEAR(cubicShortfall(180.0, false), 0.0, 1e-14);
  EXPECT_NEAR(cubicShortfall(180.0, true), 0.0, 1e-14);
}

TEST(ArcLength, QuadraticPieceMatchesTheLimitsOfSpec4) {
  // l -> (L1 + L2)/2 as theta -> pi and l -> (L1^2 + L2^2) / (2 (L1 + L2)) as theta -> 0 (here L1 = L2 = 1).
  EXPECT_NEAR(1.0 - quadraticShortfall(0.0), 0.5, 1e-12);
}

TEST(ArcLength, ParabolaHasItsClosedFormLength) {
  // Clamped quadratic with q = (0,0), (1/2,0), (1,1) is y = x^2 on [0, 1]:
  // length = sqrt(5)/2 + asinh(2)/4.
  const BSplineCurve parabola(KnotVector::clampedUniform(2, 3), PointList{Vec3::Zero(), Vec3(0.5, 0, 0), Vec3(1, 1, 0)});
  EXPECT_NEAR(arcLength(parabola), std::sqrt(5.0) / 2.0 + std::asinh(2.0) / 4.0, 1e-14);
}

TEST(ArcLength, MonotoneStraightCurveHasTheEndToEndLength) {
  std::mt19937 rng(51);
  for (int degree = 1; degree <= kMaxDegree; ++degree) {
    const KnotVector knots = test::randomKnots(rng, degree, degree + 6, true, 1);
    PointList points;
    double x = 0.0;
    for (int i = 0; i < knots.controlPointCount(); ++i) {
      x += 0.1 + 0.3 * (i % 3);
      points.push_back(Vec3(x, 2 * x, -x));
    }
    const BSplineCurve curve(knots, points);
    EXPECT_NEAR(arcLength(curve), (points.back() - points.front()).norm(), 1e-13 * x) << "degree " << degree;
  }
}

TEST(ArcLength, SubrangesAdd) {
  std::mt19937 rng(52);
  for (int trial = 0; trial < 50; ++trial) {
    const int degree = 1 + trial % kMaxDegree;
    // Rope-like curves: |C'| stays away from zero, where Gauss–Legendre converges fast (near a
    // cusp, |C'| has a kink inside a span and the fixed rule loses digits).
    const BSplineCurve curve = test::smoothCurve(rng, degree, trial % 2 == 0);
    const double a = curve.beginParameter();
    const double c = curve.endParameter();
    const double b = a + 0.37 * (c - a);
    const double whole = arcLength(curve.knots(), curve.controlPoints(), a, c);
    const double parts = arcLength(curve.knots(), curve.controlPoints(), a, b) +
                         arcLength(curve.knots(), curve.controlPoints(), b, c);
    EXPECT_NEAR(parts, whole, 1e-9 * whole);
    EXPECT_EQ(arcLength(curve.knots(), curve.controlPoints(), b, b), 0.0);
    // The polygon is never shorter than the curve it controls.
    double polygon = 0.0;
    for (size_t i = 1; i < curve.controlPoints().size(); ++i) {
      polygon += (curve.controlPoints()[i] - curve.controlPoints()[i - 1]).norm();
    }
    if (curve.knots().isClampedBegin() && curve.knots().isClampedEnd()) {
      EXPECT_LE(whole, polygon * (1 + 1e-12));
    }
  }
}

// ---- bad input ----

TEST(ArcLengthBadInput, RangeOutsideOrReversedOrNonFinite) {
  const BSplineCurve curve(KnotVector::uniform(2, 5), PointList{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 1, 0), Vec3(3, 1, 0), Vec3(4, 0, 0)});
  expectInvalid([&] { arcLength(curve.knots(), curve.controlPoints(), 1.5, 4.0); }, "s0", "1.5");
  expectInvalid([&] { arcLength(curve.knots(), curve.controlPoints(), 2.0, 5.5); }, "s1", "5.5");
  expectInvalid([&] { arcLength(curve.knots(), curve.controlPoints(), 4.0, 3.0); }, "s1", "3");
  expectInvalid([&] { arcLength(curve.knots(), curve.controlPoints(), std::nan(""), 3.0); }, "s0", "nan");
  expectInvalid([&] { arcLength(curve, ArcLengthOptions{0, 4}); }, "options.gaussPoints", "0");
  expectInvalid([&] { arcLength(curve, ArcLengthOptions{8, 0}); }, "options.piecesPerSpan", "0");
  expectInvalid([&] { arcLength(curve.knots(), PointList(4, Vec3::Zero()), 2.0, 3.0); }, "points.size()", "4");
}

}  // namespace
}  // namespace rope
