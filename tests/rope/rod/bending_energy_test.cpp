// SPDX-License-Identifier: MIT
#include "rope/rod/bending_energy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rope/spline/curve_interpolation.h"
#include "rope/spline/knot_insertion.h"
#include "tests/rope/rod/rod_test_util.h"

namespace rope {
namespace {

using test::straightRest;

constexpr double kPi = 3.14159265358979323846;

TEST(Bending, ForceAndStiffnessMatchFiniteDifferences) {
  const KnotVector knots = KnotVector::clampedUniform(3, 9, 0.0, 1.0);
  const PointList rest = straightRest(knots);
  RodIntegrals integrals;
  integrals.build(knots, rest, 0.1, 0.7, RodIntegrals::exactGaussCount(3));
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> noise(-0.1, 0.1);
  PointList q = rest;
  for (Vec3& p : q) p += Vec3(noise(rng), noise(rng), noise(rng));
  PointList force;
  bendingForces(integrals, q, force);
  double largest = 0.0;
  for (const Vec3& f : force) largest = std::max(largest, f.cwiseAbs().maxCoeff());
  SymmetricBandedMatrix K;
  assembleBendingStiffness(integrals, 9, K);
  const double eps = 1e-5;
  for (int i = 0; i < 9; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      PointList plus = q, minus = q;
      plus[static_cast<size_t>(i)][axis] += eps;
      minus[static_cast<size_t>(i)][axis] -= eps;
      const double fd = -(bendingEnergy(integrals, plus) - bendingEnergy(integrals, minus)) / (2 * eps);
      EXPECT_NEAR(force[static_cast<size_t>(i)][axis], fd, 1e-6 * largest);
      PointList fPlus, fMinus;
      bendingForces(integrals, plus, fPlus);
      bendingForces(integrals, minus, fMinus);
      for (int m = 0; m < 9; ++m) {
        const double kfd = -(fPlus[static_cast<size_t>(m)][axis] - fMinus[static_cast<size_t>(m)][axis]) / (2 * eps);
        EXPECT_NEAR(K.entry(m, i), kfd, 1e-6 * std::abs(K.entry(i, i)));
        // Isotropic: other axes are not coupled.
        EXPECT_NEAR(fPlus[static_cast<size_t>(m)][(axis + 1) % 3], fMinus[static_cast<size_t>(m)][(axis + 1) % 3],
                    1e-12 * largest);
      }
    }
  }
  // Straight lines (any placement, any uniform scale) do not bend.
  PointList line = rest;
  for (Vec3& p : line) p = Vec3(0.3, -2.0, 1.0) + 1.7 * p.x() * Vec3(0.6, 0.0, 0.8);
  EXPECT_NEAR(bendingEnergy(integrals, line), 0.0, 1e-12);  // rounding of K_b entries ~1e3
}

TEST(Bending, CircularArcHasTheEulerBernoulliEnergyAtAnyResolution) {
  // Arc of radius R and angle pi/2 laid unstretched: E = EI L / (2 R^2).
  const double radius = 0.4;
  PointList polyline;
  for (int i = 0; i <= 40; ++i) {
    const double phi = 0.5 * kPi * i / 40;
    polyline.emplace_back(radius * std::cos(phi), radius * std::sin(phi), 0.0);
  }
  const Interpolation arc = interpolatePolyline(polyline, 3);
  KnotVector knots = arc.curve.knots();
  PointList q = arc.curve.controlPoints();
  PointList rest = q;  // rest state as laid: l0' = |C'|
  const double ei = 2.0;
  RodIntegrals integrals;
  integrals.build(knots, rest, 0.1, ei, RodIntegrals::exactGaussCount(3) + 4);
  const double length = 0.5 * kPi * radius;
  const double expected = ei * length / (2.0 * radius * radius);
  const double energy = bendingEnergy(integrals, q);
  EXPECT_NEAR(energy, expected, 0.01 * expected);
  // Refinement leaves the continuous energy unchanged.
  for (double s : {0.1, 0.33, 0.5}) {
    const KnotInsertion plan = insertKnot(knots, q, s);
    plan.apply(rest);
    integrals.afterInsertion(plan, knots, rest);
  }
  EXPECT_NEAR(bendingEnergy(integrals, q), energy, 1e-6 * energy);  // quadrature of a curved rest metric
}

}  // namespace
}  // namespace rope
