// Scenario: energy behaviour of the linearised backward-Euler step (docs/method.md §8).
#include <gtest/gtest.h>

#include <cmath>

#include "rope/rod/rod.h"

namespace rope {
namespace {

// A small swinging rope, pinned at one end, released from horizontal: 6 control points so that
// 100,000 steps take well under a second. Adaptivity is off: a knot removal may change the energy by
// its (bounded) shape error, which is not what this test is about.
Rod swingingRope(double massDamping) {
  RodSettings settings;
  settings.restLength = 1.0;
  settings.linearDensity = 0.1;
  settings.youngsModulus = 1e8;
  settings.radius = 0.003;
  settings.massDamping = massDamping;
  settings.initialControlPoints = 6;
  settings.minControlPoints = 6;
  settings.adaptive = false;
  Rod rod = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(1, 0, 0));
  rod.pin(0.0);
  return rod;
}

TEST(RodEnergy, WithoutDampingTotalEnergyNeverGrowsOver100000Steps) {
  Rod rod = swingingRope(0.0);
  const double initial = rod.totalEnergy();
  double previous = initial;
  double largestGrowth = -1.0;
  int growthSteps = 0;
  for (int i = 0; i < 100000; ++i) {
    ASSERT_TRUE(rod.step(1.0 / 240).ok) << i;
    const double energy = rod.totalEnergy();
    // Rounding of the energy sum itself: a few ulps of its largest terms.
    const double tolerance = 1e-12 * (std::abs(rod.gravityEnergy()) + rod.kineticEnergy() + 1.0);
    if (energy > previous + tolerance) {
      ++growthSteps;
      largestGrowth = std::max(largestGrowth, energy - previous);
    }
    previous = energy;
  }
  EXPECT_EQ(growthSteps, 0) << "largest growth " << largestGrowth << " J";
  EXPECT_LT(previous, initial);
  std::printf("[energy] undamped: E0 %.6f J, after 100000 steps %.6f J\n", initial, previous);
}

TEST(RodEnergy, WithDampingEnergyDecaysToTheHangingMinimum) {
  Rod rod = swingingRope(2.0);
  const double initial = rod.totalEnergy();
  double previous = initial;
  for (int i = 0; i < 240 * 20; ++i) {
    ASSERT_TRUE(rod.step(1.0 / 240).ok);
    const double energy = rod.totalEnergy();
    EXPECT_LE(energy, previous + 1e-12 * (std::abs(energy) + 1.0));
    previous = energy;
  }
  // Hanging straight down from the pin: centre of mass at -L/2, E = -m g L / 2 (strain negligible).
  const double minimum = -0.1 * 9.81 * 0.5;
  EXPECT_NEAR(previous, minimum, 1e-3 * std::abs(minimum));
  EXPECT_LT(rod.kineticEnergy(), 1e-8);
}

}  // namespace
}  // namespace rope
