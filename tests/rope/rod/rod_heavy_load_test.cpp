// Scenario: a light rope holding a heavy point load (mass ratio 1000:1) at h = 1/240 s.
#include <gtest/gtest.h>

#include <cmath>

#include "rope/rod/rod.h"

namespace rope {
namespace {

class RodHeavyLoad : public ::testing::TestWithParam<double> {};

TEST_P(RodHeavyLoad, SettlesAtTheStaticStrainAndStaysStableFor60Seconds) {
  RodSettings settings;
  settings.restLength = 1.0;
  settings.linearDensity = 0.01;  // kg/m
  settings.youngsModulus = 1e9;   // EA = 78.5 kN
  settings.massDamping = 2.0;
  settings.initialControlPoints = 8;
  Rod rod = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(0, -1, 0));
  rod.pin(0.0);
  const double weight = 10.0 * 9.81;  // N, the 10 kg load
  const double h = GetParam();
  const int steps = static_cast<int>(60.0 / h + 0.5);
  double lowest = 1.0, highest = -2.0;
  for (int i = 0; i < steps; ++i) {
    rod.addForce(1.0, Vec3(0, -weight, 0));
    const StepReport report = rod.step(h);
    ASSERT_TRUE(report.ok) << "step " << i << ": " << report.failure;
    if (i > steps / 2) {
      const double y = rod.position(1.0).y();
      lowest = std::min(lowest, y);
      highest = std::max(highest, y);
    }
  }
  // Static strain: W/(EA) at the load, plus the rope's own weight (half of mu g L on average).
  const double ea = settings.axialStiffness();
  const double expected = (weight + 0.5 * settings.linearDensity * 9.81) / ea;
  const double strain = (rod.length() - 1.0) / 1.0;
  const double tolerance = 0.02;
  EXPECT_NEAR(strain, expected, tolerance * expected);
  EXPECT_NEAR(weight / ea, expected, 0.01 * expected);
  // Stable: the end stays put over the second half (no oscillation or drift beyond 1 micrometre).
  EXPECT_LT(highest - lowest, 1e-6);
  EXPECT_LT(std::abs(rod.position(1.0).x()), 1e-9);
  std::printf("[heavy load h=1/%.0f] strain %.6e, W/EA %.6e (with rope weight %.6e), end y %.9f\n", 1.0 / h, strain, weight / ea,
              expected, rod.position(1.0).y());
}

INSTANTIATE_TEST_SUITE_P(TimeSteps, RodHeavyLoad, ::testing::Values(1.0 / 240, 1.0 / 60));

}  // namespace
}  // namespace rope
