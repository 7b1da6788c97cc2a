// SPDX-License-Identifier: MIT
#include "rope/spline/bspline_curve.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "tests/rope/spline/spline_test_support.h"

namespace rope {
namespace {

using test::expectInvalid;

TEST(BSplineCurve, PositionIsTheBasisSum) {
  std::mt19937 rng(21);
  double worst = 0.0;
  for (int trial = 0; trial < 300; ++trial) {
    const int degree = 1 + trial % kMaxDegree;
    const BSplineCurve curve = test::randomCurve(rng, degree, trial % 2 == 0, degree + 1);
    const double size = test::sizeOf(curve.controlPoints());
    for (double s : test::sampleParameters(rng, curve.knots(), 10)) {
      Vec3 reference = Vec3::Zero();
      for (int i = 0; i < curve.controlPointCount(); ++i) {
        reference += test::referenceBasis(curve.knots().values(), i, degree, s, curve.endParameter()) *
                     curve.controlPoints()[static_cast<size_t>(i)];
      }
      worst = std::max(worst, (curve.position(s) - reference).norm() / (size + curve.controlPoints()[0].norm()));
      ASSERT_EQ(curve.evaluate(s).position, curve.position(s));
      ASSERT_EQ(curve.derivative(s, 0), curve.position(s));
    }
  }
  EXPECT_LE(worst, 1e-14);
}

TEST(BSplineCurve, ClampedCurvesEndOnTheirEndPoints) {
  std::mt19937 rng(22);
  for (int degree = 1; degree <= kMaxDegree; ++degree) {
    const BSplineCurve curve = test::randomCurve(rng, degree, true, 1);
    // Rounding only: the end basis function is 1 to a few ulps, the others vanish exactly.
    const Vec3& first = curve.controlPoints().front();
    const Vec3& last = curve.controlPoints().back();
    EXPECT_LE((curve.position(curve.beginParameter()) - first).norm(), 1e-15 * first.norm());
    EXPECT_LE((curve.position(curve.endParameter()) - last).norm(), 1e-15 * last.norm());
  }
}

TEST(BSplineCurve, DerivativesAgreeWithCentralDifferences) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> unit(0.1, 0.9);
  double worst1 = 0.0;
  double worst2 = 0.0;
  for (int trial = 0; trial < 300; ++trial) {
    const int degree = 1 + trial % kMaxDegree;
    const BSplineCurve curve = test::randomCurve(rng, degree, trial % 2 == 1, degree);
    const KnotVector& knots = curve.knots();
    const double size = test::sizeOf(curve.controlPoints());
    for (int k = degree; k < knots.controlPointCount(); ++k) {
      const double a = knots[k];
      const double b = knots[k + 1];
      if (!(b > a)) continue;
      const double s = a + (b - a) * unit(rng);
      // Central differences with Richardson extrapolation, (4 D(h/2) - D(h)) / 3: error O(h^4).
      const double h = 1e-3 * (b - a);
      const CurvePoint at = curve.evaluate(s);
      const CurvePoint plus = curve.evaluate(s + h);
      const CurvePoint minus = curve.evaluate(s - h);
      const CurvePoint halfPlus = curve.evaluate(s + 0.5 * h);
      const CurvePoint halfMinus = curve.evaluate(s - 0.5 * h);
      const Vec3 fd1 = (4 * (halfPlus.position - halfMinus.position) / h - (plus.position - minus.position) / (2 * h)) / 3;
      const Vec3 fd2 = (4 * (halfPlus.firstDerivative - halfMinus.firstDerivative) / h -
                        (plus.firstDerivative - minus.firstDerivative) / (2 * h)) / 3;
      // Scaled by size / span^r, the natural size of the r-th derivative.
      worst1 = std::max(worst1, (fd1 - at.firstDerivative).norm() * (b - a) / size);
      worst2 = std::max(worst2, (fd2 - at.secondDerivative).norm() * (b - a) * (b - a) / size);
      EXPECT_EQ(curve.derivative(s, 1), at.firstDerivative);
      EXPECT_EQ(curve.derivative(s, 2), at.secondDerivative);
    }
  }
  std::printf("curve derivatives: max scaled |FD - C'| %.3g, |FD - C''| %.3g\n", worst1, worst2);
  EXPECT_LE(worst1, 1e-9);
  EXPECT_LE(worst2, 1e-9);
}

TEST(BSplineCurve, BatchEvaluationEqualsPointEvaluationInAnyOrder) {
  std::mt19937 rng(24);
  for (int trial = 0; trial < 100; ++trial) {
    const int degree = 1 + trial % kMaxDegree;
    const BSplineCurve curve = test::randomCurve(rng, degree, trial % 2 == 0, degree);
    std::vector<double> s = test::sampleParameters(rng, curve.knots(), 50);
    for (int order = 0; order < 3; ++order) {
      if (order == 1) std::sort(s.begin(), s.end());
      if (order == 2) std::reverse(s.begin(), s.end());
      std::vector<CurvePoint> points;
      PointList positions;
      curve.evaluate(s, points);
      curve.positions(s, positions);
      ASSERT_EQ(points.size(), s.size());
      ASSERT_EQ(positions.size(), s.size());
      for (size_t i = 0; i < s.size(); ++i) {
        const CurvePoint single = curve.evaluate(s[i]);
        ASSERT_EQ(points[i].position, single.position);
        ASSERT_EQ(points[i].firstDerivative, single.firstDerivative);
        ASSERT_EQ(points[i].secondDerivative, single.secondDerivative);
        ASSERT_EQ(positions[i], single.position);
      }
    }
  }
}

TEST(BSplineCurve, FreeFunctionsMatchTheClass) {
  std::mt19937 rng(25);
  const BSplineCurve curve = test::randomCurve(rng, 3, false, 2);
  for (double s : test::sampleParameters(rng, curve.knots(), 20)) {
    const CurvePoint a = evaluateCurve(curve.knots(), curve.controlPoints(), s);
    EXPECT_EQ(a.position, curve.position(s));
    EXPECT_EQ(a.firstDerivative, curve.derivative(s));
    EXPECT_EQ(curvePosition(curve.knots(), curve.controlPoints(), s), curve.position(s));
  }
}

// curvePositionNear is curvePosition bit for bit from any span hint, and leaves the hint at s's
// span; it rejects what curvePosition rejects.
TEST(BSplineCurve, PositionAndEvaluationNearAHintAreThoseWithoutOne) {
  std::mt19937 rng(26);
  for (int trial = 0; trial < 60; ++trial) {
    const int degree = 1 + trial % kMaxDegree;
    const BSplineCurve curve = test::randomCurve(rng, degree, trial % 2 == 0, degree);
    const int last = curve.knots().controlPointCount() - 1;
    for (double s : test::sampleParameters(rng, curve.knots(), 20)) {
      for (const int start : {-1, degree, last, last + 5}) {
        int span = start;
        ASSERT_EQ(curvePositionNear(curve.knots(), curve.controlPoints(), s, span), curve.position(s));
        ASSERT_EQ(span, curve.knots().findSpan(s));
        span = start;
        const CurvePoint near = evaluateCurveNear(curve.knots(), curve.controlPoints(), s, span);
        const CurvePoint searched = curve.evaluate(s);
        ASSERT_EQ(near.position, searched.position);
        ASSERT_EQ(near.firstDerivative, searched.firstDerivative);
        ASSERT_EQ(near.secondDerivative, searched.secondDerivative);
        ASSERT_EQ(span, curve.knots().findSpan(s));
      }
    }
  }
  const BSplineCurve curve(KnotVector::uniform(3, 6), PointList(6, Vec3::Ones()));  // valid [3, 6]
  int span = 3;
  expectInvalid([&] { curvePositionNear(curve.knots(), curve.controlPoints(), 6.5, span); }, "s", "6.5");
  expectInvalid([&] { curvePositionNear(curve.knots(), curve.controlPoints(), std::nan(""), span); }, "s", "nan");
  expectInvalid([&] { evaluateCurveNear(curve.knots(), curve.controlPoints(), 2.5, span); }, "s", "2.5");
  expectInvalid([&] { evaluateCurveNear(curve.knots(), curve.controlPoints(), std::nan(""), span); }, "s", "nan");
  EXPECT_EQ(span, 3);
}

TEST(BSplineCurve, SetControlPointsReplacesThem) {
  BSplineCurve curve(KnotVector::clampedUniform(2, 4), PointList(4, Vec3::Zero()));
  curve.setControlPoint(3, Vec3(1, 2, 3));
  EXPECT_EQ(curve.position(1.0), Vec3(1, 2, 3));
  curve.setControlPoints(PointList(4, Vec3(0, 0, 5)));
  EXPECT_EQ(curve.position(0.3), Vec3(0, 0, 5));
}

// ---- bad input: names the parameter and value; the curve is unchanged ----

TEST(BSplineCurveBadInput, TooFewOrTooManyControlPoints) {
  expectInvalid([] { BSplineCurve(KnotVector::clampedUniform(3, 5), PointList(4, Vec3::Zero())); },
                "controlPoints.size()", "4");
  BSplineCurve curve(KnotVector::clampedUniform(3, 5), PointList(5, Vec3::Ones()));
  const PointList before = curve.controlPoints();
  expectInvalid([&] { curve.setControlPoints(PointList(6, Vec3::Zero())); }, "points.size()", "6");
  expectInvalid([&] { curve.setControlPoint(5, Vec3::Zero()); }, "i", "5");
  EXPECT_EQ(curve.controlPoints(), before);
}

TEST(BSplineCurveBadInput, NonFinitePoints) {
  const double inf = std::numeric_limits<double>::infinity();
  PointList points(5, Vec3::Zero());
  points[2] = Vec3(0, std::nan(""), 0);
  expectInvalid([&] { BSplineCurve(KnotVector::clampedUniform(3, 5), points); }, "controlPoints[2]", "nan");
  BSplineCurve curve(KnotVector::clampedUniform(3, 5), PointList(5, Vec3::Ones()));
  const PointList before = curve.controlPoints();
  expectInvalid([&] { curve.setControlPoint(1, Vec3(inf, 0, 0)); }, "point", "inf");
  PointList replacement(5, Vec3::Zero());
  replacement[4] = Vec3(0, 0, -inf);
  expectInvalid([&] { curve.setControlPoints(replacement); }, "points[4]", "-inf");
  EXPECT_EQ(curve.controlPoints(), before);
}

TEST(BSplineCurveBadInput, ParameterOutsideValidRangeOrNonFinite) {
  const BSplineCurve curve(KnotVector::uniform(3, 6), PointList(6, Vec3::Ones()));  // valid [3, 6]
  expectInvalid([&] { curve.position(2.5); }, "s", "2.5");
  expectInvalid([&] { curve.derivative(6.25); }, "s", "6.25");
  expectInvalid([&] { curve.evaluate(std::nan("")); }, "s", "nan");
  expectInvalid([&] { curve.position(std::numeric_limits<double>::infinity()); }, "s", "inf");
  expectInvalid([&] { curve.derivative(4.0, 3); }, "order", "3");
  // Batch: everything is validated before anything is written.
  std::vector<CurvePoint> out(2);
  out[0].position = Vec3(7, 7, 7);
  expectInvalid([&] { curve.evaluate(std::vector<double>{3.0, 4.0, 5.0, 7.5}, out); }, "s[3]", "7.5");
  EXPECT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].position, Vec3(7, 7, 7));
  PointList positions(1, Vec3(8, 8, 8));
  expectInvalid([&] { curve.positions(std::vector<double>{std::nan("")}, positions); }, "s[0]", "nan");
  EXPECT_EQ(positions, PointList(1, Vec3(8, 8, 8)));
}

}  // namespace
}  // namespace rope
