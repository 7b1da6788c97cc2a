// SPDX-License-Identifier: MIT
#include "rope/spline/curve_split.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "rope/spline/bspline_basis.h"
#include "rope/spline/bspline_curve.h"
#include "tests/rope/spline/spline_test_support.h"

namespace rope {
namespace {

using test::expectInvalid;

// A parameter strictly inside the valid range; every fourth one is an existing interior knot.
double splitParameter(std::mt19937& rng, const KnotVector& knots, int trial) {
  std::uniform_real_distribution<double> unit(0.02, 0.98);
  if (trial % 4 == 0) {
    for (double t : knots.values()) {
      if (t > knots.validBegin() && t < knots.validEnd()) return t;
    }
  }
  return knots.validBegin() + (knots.validEnd() - knots.validBegin()) * unit(rng);
}

TEST(CurveSplit, PiecesReproduceTheirSideOfTheCurve) {
  std::mt19937 rng(31);
  double worst = 0.0;
  double worstVelocity = 0.0;
  for (int trial = 0; trial < 500; ++trial) {
    const int degree = 1 + trial % kMaxDegree;
    const BSplineCurve curve = test::randomCurve(rng, degree, trial % 2 == 0, degree + 1);
    const double s = splitParameter(rng, curve.knots(), trial);
    const auto pieces = curve.split(s);
    const BSplineCurve& left = pieces.first;
    const BSplineCurve& right = pieces.second;
    ASSERT_EQ(left.beginParameter(), curve.beginParameter());
    ASSERT_EQ(left.endParameter(), s);
    ASSERT_EQ(right.beginParameter(), s);
    ASSERT_EQ(right.endParameter(), curve.endParameter());
    EXPECT_EQ(left.knots().multiplicity(s), degree + 1);
    EXPECT_EQ(right.knots().multiplicity(s), degree + 1);
    // Velocities split with the same plan keep the velocity field on each side.
    PointList velocities;
    for (int i = 0; i < curve.controlPointCount(); ++i) velocities.push_back(Vec3(std::sin(i + 0.3 * trial), std::cos(1.7 * i), 1.0 / (1 + i)));
    const CurveSplitPlan plan = planCurveSplit(curve.knots(), s);
    const auto velocityPieces = plan.apply(velocities);
    ASSERT_EQ(velocityPieces.first.size(), left.controlPoints().size());
    ASSERT_EQ(velocityPieces.second.size(), right.controlPoints().size());
    const double size = test::sizeOf(curve.controlPoints());
    const double velocitySize = test::sizeOf(velocities);
    for (int i = 0; i <= 400; ++i) {
      const double u = i / 400.0;
      const double a = std::min(s, curve.beginParameter() + (s - curve.beginParameter()) * u);
      const double b = std::min(curve.endParameter(), s + (curve.endParameter() - s) * u);
      // At s itself a curve already cut there (multiplicity d+1) jumps; the left piece holds the left limit.
      if (a < s || curve.knots().multiplicity(s) <= degree) {
        worst = std::max(worst, (left.position(a) - curve.position(a)).norm() / size);
      }
      worst = std::max(worst, (right.position(b) - curve.position(b)).norm() / size);
      // The original velocity field, evaluated from the left at s (its left limit) when it jumps there.
      if (a < s) {
        worstVelocity = std::max(worstVelocity, (curvePosition(left.knots(), velocityPieces.first, a) -
                                                 curvePosition(curve.knots(), velocities, a)).norm() / velocitySize);
      }
      worstVelocity = std::max(worstVelocity, (curvePosition(right.knots(), velocityPieces.second, b) -
                                               curvePosition(curve.knots(), velocities, b)).norm() / velocitySize);
    }
  }
  std::printf("split: max |C_piece - C| / size %.3g, velocity field %.3g\n", worst, worstVelocity);
  EXPECT_LE(worst, 1e-12);
  EXPECT_LE(worstVelocity, 1e-12);
}

TEST(CurveSplit, SidesShareNoBasisFunction) {
  std::mt19937 rng(8);
  for (int trial = 0; trial < 200; ++trial) {
    const int degree = 1 + trial % kMaxDegree;
    const BSplineCurve curve = test::randomCurve(rng, degree, trial % 3 == 0, degree);
    const double s = splitParameter(rng, curve.knots(), trial);
    const CurveSplitPlan plan = planCurveSplit(curve.knots(), s);
    // The knot vector after the planned insertions.
    KnotVector split = curve.knots();
    for (const KnotInsertion& insertion : plan.insertions) split.insertValue(insertion.parameter);
    ASSERT_EQ(split.multiplicity(s), degree + 1);
    const int r = plan.rightFirstPoint;
    ASSERT_EQ(plan.leftKnots.controlPointCount(), r);
    ASSERT_EQ(plan.rightKnots.controlPointCount(), split.controlPointCount() - r);
    for (int j = 0; j <= 100; ++j) {
      const double u = j / 100.0;
      const double leftSample = split.validBegin() + (s - split.validBegin()) * u * 0.999;  // < s
      const double rightSample = std::min(split.validEnd(), s + (split.validEnd() - s) * (0.001 + 0.999 * u));  // > s
      for (int i = 0; i < split.controlPointCount(); ++i) {
        if (i < r) {
          ASSERT_EQ(basisFunction(split, i, rightSample), 0.0) << "left function " << i << " at " << rightSample;
        } else {
          ASSERT_EQ(basisFunction(split, i, leftSample), 0.0) << "right function " << i << " at " << leftSample;
        }
      }
    }
  }
}

TEST(CurveSplit, AlreadyCutKnotNeedsNoInsertion) {
  const KnotVector knots(2, {0, 0, 0, 1, 1, 1, 2, 2, 2});
  const CurveSplitPlan plan = planCurveSplit(knots, 1.0);
  EXPECT_TRUE(plan.insertions.empty());
  EXPECT_EQ(plan.rightFirstPoint, 3);
  EXPECT_EQ(plan.leftKnots.values(), (std::vector<double>{0, 0, 0, 1, 1, 1}));
  EXPECT_EQ(plan.rightKnots.values(), (std::vector<double>{1, 1, 1, 2, 2, 2}));
  const CurveSplitPlan fresh = planCurveSplit(KnotVector::clampedUniform(3, 4), 0.5);
  EXPECT_EQ(fresh.insertions.size(), 4u);
}

// ---- bad input ----

TEST(CurveSplitBadInput, SplittingAtAnEndOrOutside) {
  const BSplineCurve curve(KnotVector::uniform(3, 7), PointList(7, Vec3(0, 0, 2)));
  expectInvalid([&] { curve.split(curve.beginParameter()); }, "s", "3");
  expectInvalid([&] { curve.split(curve.endParameter()); }, "s", "7");
  expectInvalid([&] { curve.split(9.0); }, "s", "9");
  expectInvalid([&] { planCurveSplit(curve.knots(), std::nan("")); }, "s", "nan");
  expectInvalid([&] { planCurveSplit(curve.knots(), -std::numeric_limits<double>::infinity()); }, "s", "-inf");
  EXPECT_EQ(curve.knots().values(), KnotVector::uniform(3, 7).values());  // split() is const
}

}  // namespace
}  // namespace rope
