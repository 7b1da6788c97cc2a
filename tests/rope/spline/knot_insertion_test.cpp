// SPDX-License-Identifier: MIT
#include "rope/spline/knot_insertion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "rope/spline/bspline_curve.h"
#include "tests/rope/spline/spline_test_support.h"

namespace rope {
namespace {

using test::expectInvalid;

// Acceptance: 10,000 random insertions on random curves of degree 1..5, clamped and unclamped,
// non-uniform knots with repeats. After every insertion C and C' are compared with the original
// curve, and the velocity field sum_i v_i b_i(s) with the original velocity field.
TEST(KnotInsertion, TenThousandRandomInsertionsLeaveCurveAndVelocityFieldUnchanged) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int insertions = 0;
  double worstPosition = 0.0;    // |dC| / size
  double worstDerivative = 0.0;  // |dC'| / (size / shortest span)
  double worstVelocity = 0.0;
  int curveIndex = 0;
  while (insertions < 10000) {
    const int degree = 1 + curveIndex % kMaxDegree;
    const bool clamped = (curveIndex / kMaxDegree) % 2 == 0;
    ++curveIndex;
    const BSplineCurve original = test::randomCurve(rng, degree, clamped, degree);
    // A random velocity per control point, with its own scale.
    PointList velocities;
    for (int i = 0; i < original.controlPointCount(); ++i) {
      velocities.push_back(Vec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5) * 3.0);
    }
    const double size = test::sizeOf(original.controlPoints());
    const std::vector<double> samples = test::sampleParameters(rng, original.knots(), 24);
    std::vector<CurvePoint> before;
    original.evaluate(samples, before);
    std::vector<Vec3> velocityBefore;
    for (double s : samples) velocityBefore.push_back(curvePosition(original.knots(), velocities, s));

    BSplineCurve refined = original;
    PointList refinedVelocities = velocities;
    for (int step = 0; step < 20 && insertions < 10000; ++step) {
      const KnotVector& knots = refined.knots();
      double s = knots.validBegin() + (knots.validEnd() - knots.validBegin()) * unit(rng);
      // One in four insertions lands on an existing interior knot (raising its multiplicity).
      if (step % 4 == 3) {
        std::vector<double> interior;
        for (double t : knots.values()) {
          if (t > knots.validBegin() && t < knots.validEnd() && knots.multiplicity(t) <= degree) interior.push_back(t);
        }
        if (!interior.empty()) s = interior[static_cast<size_t>(unit(rng) * static_cast<double>(interior.size())) % interior.size()];
      }
      if (!(s > knots.validBegin() && s < knots.validEnd())) continue;
      const KnotInsertion plan = refined.insertKnot(s);
      plan.apply(refinedVelocities);
      ++insertions;
      ASSERT_EQ(refined.controlPointCount(), static_cast<int>(refinedVelocities.size()));
    }
    std::vector<CurvePoint> after;
    refined.evaluate(samples, after);
    // C' = sum q_i b_i' with b_i' = O(1/h): rounding in the refined curve's derivative is
    // eps * size / h for its shortest span h, so that is the scale C' is compared on.
    const double h = std::min(test::shortestSpan(original.knots()), test::shortestSpan(refined.knots()));
    const double speedScale = size / h;
    const double velocityScale = test::sizeOf(velocities);  // the field itself, not a derivative
    for (size_t i = 0; i < samples.size(); ++i) {
      worstPosition = std::max(worstPosition, (after[i].position - before[i].position).norm() / size);
      worstDerivative =
          std::max(worstDerivative, (after[i].firstDerivative - before[i].firstDerivative).norm() / speedScale);
      const Vec3 velocityAfter = curvePosition(refined.knots(), refinedVelocities, samples[i]);
      worstVelocity = std::max(worstVelocity, (velocityAfter - velocityBefore[i]).norm() / velocityScale);
    }
  }
  RecordProperty("worstPosition", std::to_string(worstPosition));
  RecordProperty("worstDerivative", std::to_string(worstDerivative));
  std::printf("insertions %d on %d curves: max |dC|/size %.3g, max |dC'|/(size/h_min) %.3g, "
              "max |dv|/(|v| box) %.3g\n",
              insertions, curveIndex, worstPosition, worstDerivative, worstVelocity);
  EXPECT_LE(worstPosition, 1e-12);
  EXPECT_LE(worstDerivative, 1e-12);
  EXPECT_LE(worstVelocity, 1e-12);
}

TEST(KnotInsertion, PlanMatchesBoehmFormula) {
  // Clamped quadratic on {0,0,0,1,2,3,3,3}; insert 1.5 into span k = 3.
  const KnotVector knots(2, {0, 0, 0, 1, 2, 3, 3, 3});
  const KnotInsertion plan = planKnotInsertion(knots, 1.5);
  EXPECT_EQ(plan.span, 3);
  EXPECT_EQ(plan.degree, 2);
  EXPECT_EQ(plan.firstChanged(), 2);
  EXPECT_EQ(plan.lastChanged(), 3);
  // a_i = (s* - s_i) / (s_{i+d} - s_i): a_2 = (1.5 - 0)/(2 - 0), a_3 = (1.5 - 1)/(3 - 1).
  EXPECT_DOUBLE_EQ(plan.alpha[0], 0.75);
  EXPECT_DOUBLE_EQ(plan.alpha[1], 0.25);
  std::vector<double> values{1, 2, 4, 8, 16};
  plan.apply(values);
  const std::vector<double> expected{1, 2, 0.75 * 4 + 0.25 * 2, 0.25 * 8 + 0.75 * 4, 8, 16};
  EXPECT_EQ(values, expected);
}

TEST(KnotInsertion, RaisingMultiplicityToDegreePlusOneInterpolatesThePoint) {
  std::mt19937 rng(7);
  for (int degree = 1; degree <= kMaxDegree; ++degree) {
    BSplineCurve curve = test::randomCurve(rng, degree, degree % 2 == 0, 1);
    const double s = 0.5 * (curve.beginParameter() + curve.endParameter());
    const Vec3 expected = curve.position(s);
    while (curve.knots().multiplicity(s) < degree + 1) curve.insertKnot(s);
    // With multiplicity d+1 exactly one control point carries C(s): the curve passes through it.
    const int k = curve.knots().findSpan(s);
    const Vec3& corner = curve.controlPoints()[static_cast<size_t>(k - degree)];
    EXPECT_LE((corner - expected).norm(), 1e-12 * test::sizeOf(curve.controlPoints())) << "degree " << degree;
  }
}

// ---- bad input ----

TEST(KnotInsertionBadInput, ParameterOutsideValidRangeOrAtAnEnd) {
  std::mt19937 rng(3);
  BSplineCurve curve = test::randomCurve(rng, 3, false, 1);
  const BSplineCurve before = curve;
  const double end = curve.endParameter();
  expectInvalid([&] { curve.insertKnot(end + 0.25); }, "s", formatValue(end + 0.25));
  expectInvalid([&] { curve.insertKnot(end); }, "s", formatValue(end));
  expectInvalid([&] { curve.insertKnot(curve.beginParameter()); }, "s", formatValue(curve.beginParameter()));
  EXPECT_EQ(curve.knots().values(), before.knots().values());
  EXPECT_EQ(curve.controlPoints(), before.controlPoints());
}

TEST(KnotInsertionBadInput, NonFiniteParameter) {
  BSplineCurve curve(KnotVector::uniform(2, 5), PointList(5, Vec3(1, 2, 3)));
  const BSplineCurve before = curve;
  expectInvalid([&] { curve.insertKnot(std::nan("")); }, "s", "nan");
  expectInvalid([&] { curve.insertKnot(std::numeric_limits<double>::infinity()); }, "s", "inf");
  EXPECT_EQ(curve.knots().values(), before.knots().values());
  EXPECT_EQ(curve.controlPoints(), before.controlPoints());
}

TEST(KnotInsertionBadInput, BeyondMultiplicityDegreePlusOne) {
  BSplineCurve curve(KnotVector(2, {0, 0, 0, 1, 1, 1, 2, 2, 2}), PointList(6, Vec3(0, 1, 0)));
  const BSplineCurve before = curve;
  expectInvalid([&] { curve.insertKnot(1.0); }, "s", "1");
  EXPECT_EQ(curve.knots().values(), before.knots().values());
  EXPECT_EQ(curve.controlPoints(), before.controlPoints());
}

TEST(KnotInsertionBadInput, PointCountMismatchAndNonFinitePoints) {
  KnotVector knots = KnotVector::clampedUniform(3, 6);
  PointList points(5, Vec3::Zero());
  const std::vector<double> knotsBefore = knots.values();
  expectInvalid([&] { insertKnot(knots, points, 0.5); }, "points.size()", "5");
  points.assign(6, Vec3::Zero());
  points[2] = Vec3(0, std::numeric_limits<double>::infinity(), 0);
  const PointList pointsBefore = points;
  expectInvalid([&] { insertKnot(knots, points, 0.5); }, "points[2]", "inf");
  EXPECT_EQ(knots.values(), knotsBefore);
  EXPECT_EQ(points, pointsBefore);
}

}  // namespace
}  // namespace rope
