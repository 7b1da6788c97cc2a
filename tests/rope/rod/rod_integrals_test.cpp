// SPDX-License-Identifier: MIT
#include "rope/rod/rod_integrals.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rope/common/error.h"
#include "rope/spline/bspline_basis.h"
#include "rope/spline/gauss_legendre.h"
#include "rope/spline/knot_insertion.h"
#include "rope/spline/knot_removal.h"
#include "tests/rope/rod/rod_test_util.h"

namespace rope {
namespace {

using test::straightRest;

// Independent reference: integral over the whole valid range of f(s), 24 Gauss points per span, with
// the single-function evaluator basisFunction() (no shared code with the rod's factored storage).
template <class F>
double integrate(const KnotVector& knots, F f) {
  const GaussRule rule = gaussLegendre(24);
  double sum = 0.0;
  for (int k = knots.degree(); k < knots.controlPointCount(); ++k) {
    const double a = knots[k];
    const double b = knots[k + 1];
    if (!(b > a)) continue;
    for (int g = 0; g < rule.count; ++g) {
      const double s = 0.5 * (a + b) + 0.5 * (b - a) * rule.nodes[g];
      sum += 0.5 * (b - a) * rule.weights[g] * f(s);
    }
  }
  return sum;
}

KnotVector nonUniformKnots() {
  return KnotVector(3, {0.0, 0.0, 0.0, 0.0, 0.1, 0.35, 0.4, 0.7, 0.85, 1.0, 1.0, 1.0, 1.0});
}

TEST(RodIntegrals, SpecTensorsMatchIndependentQuadrature) {
  const KnotVector knots = nonUniformKnots();
  // A curved but regular rest curve makes l0' non-constant; the rod then uses 4 extra points.
  PointList rest = straightRest(knots);
  for (size_t i = 0; i < rest.size(); ++i) rest[i].y() = 0.1 * std::sin(3.0 * rest[i].x());
  RodIntegrals integrals;
  integrals.build(knots, rest, 0.2, 0.0, RodIntegrals::exactGaussCount(3) + 4);
  auto l0 = [&](double s) {
    Vec3 t = Vec3::Zero();
    for (int i = 0; i < knots.controlPointCount(); ++i) t += basisFunction(knots, i, s, 1) * rest[static_cast<size_t>(i)];
    return t.norm();
  };
  const int quads[][4] = {{2, 2, 2, 2}, {1, 2, 3, 4}, {3, 4, 4, 5}, {0, 0, 1, 2}, {5, 6, 7, 8}, {4, 5, 6, 7}};
  for (const auto& idx : quads) {
    const double expected = integrate(knots, [&](double s) {
      const double l = l0(s);
      return basisFunction(knots, idx[0], s, 1) * basisFunction(knots, idx[1], s, 1) *
             basisFunction(knots, idx[2], s, 1) * basisFunction(knots, idx[3], s, 1) / (l * l * l);
    });
    EXPECT_NEAR(integrals.B4(idx[0], idx[1], idx[2], idx[3]), expected, 1e-6 * std::abs(expected) + 1e-9);
    // Full symmetry.
    EXPECT_DOUBLE_EQ(integrals.B4(idx[0], idx[1], idx[2], idx[3]), integrals.B4(idx[3], idx[2], idx[1], idx[0]));
  }
  for (int i = 0; i < 9; ++i) {
    for (int m = i; m < std::min(9, i + 4); ++m) {
      const double expected = integrate(knots, [&](double s) {
        return basisFunction(knots, i, s, 1) * basisFunction(knots, m, s, 1) / l0(s);
      });
      EXPECT_NEAR(integrals.B2(i, m), expected, 1e-6 * std::abs(expected) + 1e-9) << i << "," << m;
    }
  }
  EXPECT_EQ(integrals.B4(0, 5, 5, 5), 0.0);  // no common span: locality
}

TEST(RodIntegrals, ExactForStraightRestAndMassAddsUp) {
  const KnotVector knots = nonUniformKnots();
  const PointList rest = straightRest(knots);
  RodIntegrals integrals;
  const double mu = 0.3;
  integrals.build(knots, rest, mu, 2.0, RodIntegrals::exactGaussCount(3));
  double restLength = 0.0, massSum = 0.0, gravitySum = 0.0;
  for (int j = 0; j < integrals.spanCount(); ++j) {
    const SpanView span = integrals.span(j);
    restLength += span.restLength;
    for (int a = 0; a < 4; ++a) {
      gravitySum += span.gravity[a];
      for (int b = 0; b < 4; ++b) massSum += span.mass[a * 4 + b];
    }
  }
  EXPECT_NEAR(restLength, 1.0, 1e-14);
  EXPECT_NEAR(massSum, mu, 1e-14);  // partition of unity: 1^T M 1 = mu L
  EXPECT_NEAR(gravitySum, mu, 1e-14);
  // The exact (5-point) rule equals the 24-point reference for the quartic integrand.
  const double expected = integrate(knots, [&](double s) {
    const double b = basisFunction(knots, 3, s, 1);
    return b * b * b * b;
  });
  EXPECT_NEAR(integrals.B4(3, 3, 3, 3), expected, 1e-13 * expected);
}

void expectSameIntegrals(const RodIntegrals& a, const RodIntegrals& b) {
  ASSERT_EQ(a.spanCount(), b.spanCount());
  const int local = a.degree() + 1;
  for (int j = 0; j < a.spanCount(); ++j) {
    const SpanView x = a.span(j);
    const SpanView y = b.span(j);
    EXPECT_NEAR(x.restLength, y.restLength, 1e-14);
    for (int g = 0; g < a.gaussCount(); ++g) {
      EXPECT_NEAR(x.w1[g], y.w1[g], 1e-14);
      EXPECT_NEAR(x.w3[g], y.w3[g], 1e-14);
      for (int k = 0; k < local; ++k) EXPECT_NEAR(x.dBasis[g * local + k], y.dBasis[g * local + k], 1e-11);
    }
    for (int k = 0; k < local * local; ++k) {
      EXPECT_NEAR(x.mass[k], y.mass[k], 1e-14);
      EXPECT_NEAR(x.bending[k], y.bending[k], 1e-8 * std::abs(y.bending[k]) + 1e-8);
    }
  }
}

TEST(RodIntegrals, InsertionAndRemovalUpdatesEqualARebuild) {
  KnotVector knots = KnotVector::clampedUniform(3, 12, 0.0, 2.0);
  PointList rest = straightRest(knots);
  RodIntegrals integrals;
  integrals.build(knots, rest, 0.1, 0.5, RodIntegrals::exactGaussCount(3));
  for (double s : {0.93, 0.05, 1.99, 1.0}) {
    const KnotInsertion plan = insertKnot(knots, rest, s);
    integrals.afterInsertion(plan, knots, rest);
    RodIntegrals rebuilt;
    rebuilt.build(knots, rest, 0.1, 0.5, RodIntegrals::exactGaussCount(3));
    expectSameIntegrals(integrals, rebuilt);
  }
  for (double s : {0.93, 0.05, 1.99, 1.0}) {
    const KnotRemoval plan = removeKnot(knots, rest, s);
    integrals.afterRemoval(plan, knots, rest);
    RodIntegrals rebuilt;
    rebuilt.build(knots, rest, 0.1, 0.5, RodIntegrals::exactGaussCount(3));
    expectSameIntegrals(integrals, rebuilt);
  }
  EXPECT_EQ(integrals.spanCount(), 12 - 3);
}

TEST(RodIntegrals, DegenerateRestCurveIsRejected) {
  const KnotVector knots = KnotVector::clampedUniform(3, 6);
  const PointList rest(6, Vec3(1.0, 2.0, 3.0));  // a point: l0' = 0
  RodIntegrals integrals;
  EXPECT_THROW(integrals.build(knots, rest, 1.0, 0.0, 5), InvalidArgument);
}

}  // namespace
}  // namespace rope
