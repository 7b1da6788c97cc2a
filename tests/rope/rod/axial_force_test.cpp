// SPDX-License-Identifier: MIT
// rope::axialForce: the tension a rod carries as its stretching quadrature samples it — exact for a
// uniform stretch on any knots and for a heavy load hanging from a pin (W plus the rope's weight
// below), where the pointwise Green–Lagrange tension of the cubic ripples between the samples.
#include "rope/rod/axial_force.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "rope/common/error.h"

namespace rope {
namespace {

double greenLagrangeTension(double ea, double stretch) { return 0.5 * ea * (stretch * stretch - 1.0) * stretch; }

// The pointwise tension of the cubic at s (what RopeObject::tension read before).
double pointwiseTension(const Rod& rod, double s) {
  return greenLagrangeTension(rod.settings().axialStiffness(), 1.0 + rod.strain(s));
}

TEST(AxialForce, UniformStretchIsExactOnAnyKnots) {
  for (const StretchingQuadrature rule : {StretchingQuadrature::kLockingFree, StretchingQuadrature::kExact}) {
    RodSettings settings;
    settings.restLength = 1.0;
    settings.adaptive = false;
    settings.stretchingQuadrature = rule;
    // 1 m of rest length laid over 1.01 m: a uniform stretch of 1.01, on uneven spans.
    Rod rod = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(1.01, 0, 0));
    for (const double s : {0.05, 0.07, 0.5, 0.93}) rod.insertKnot(s);
    const double expected = greenLagrangeTension(settings.axialStiffness(), 1.01);
    for (int i = 0; i <= 40; ++i) {
      const double s = rod.beginParameter() + (rod.endParameter() - rod.beginParameter()) * i / 40.0;
      EXPECT_NEAR(axialForce(rod, s), expected, 1e-10 * expected) << "s = " << s;
    }
  }
}

TEST(AxialForce, HeavyLoadCarriesTheLoadPlusTheWeightBelowAtEveryPoint) {
  // 10 kg on 1 m of 0.01 kg/m rope (EA = 78.5 kN), settled: T(s) = W + mu g (L - s), s the rest
  // arclength. Extra knots near the load make the spans uneven there.
  RodSettings settings;
  settings.restLength = 1.0;
  settings.linearDensity = 0.01;
  settings.youngsModulus = 1e9;
  settings.massDamping = 2.0;
  settings.initialControlPoints = 8;
  Rod rod = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(0, -1, 0));
  for (const double s : {0.9, 0.95, 0.97}) rod.insertKnot(s);
  rod.pin(0.0);
  const double weight = 10.0 * 9.81;
  for (int i = 0; i < 240 * 20; ++i) {
    rod.addForce(1.0, Vec3(0, -weight, 0));
    ASSERT_TRUE(rod.step(1.0 / 240.0).ok);
  }
  double worst = 0.0, worstPointwise = 0.0;
  for (int i = 0; i <= 40; ++i) {
    const double s = i / 40.0;
    const double expected = weight + settings.linearDensity * 9.81 * (1.0 - s);
    worst = std::max(worst, std::abs(axialForce(rod, s) / expected - 1.0));
    worstPointwise = std::max(worstPointwise, std::abs(pointwiseTension(rod, s) / expected - 1.0));
  }
  std::printf("[axial force] heavy load: readout within %.2e of W + mu g (L - s); pointwise tension within %.2e\n",
              worst, worstPointwise);
  RecordProperty("worst_relative_error", std::to_string(worst));
  // Measured: 3.7e-8 (the rope still settling after 20 s of mass damping).
  EXPECT_LT(worst, 1e-7);
}

TEST(AxialForce, ParameterOutsideTheRodIsRejected) {
  const Rod rod = Rod::fromSegment(RodSettings{}, Vec3(0, 0, 0), Vec3(1, 0, 0));
  for (const double s : {-0.1, 1.5, std::nan("")}) {
    try {
      axialForce(rod, s);
      ADD_FAILURE() << "s = " << s << " accepted";
    } catch (const InvalidArgument& error) {
      EXPECT_EQ(error.parameter(), "s");
    }
  }
}

}  // namespace
}  // namespace rope
