// SPDX-License-Identifier: MIT
// Cutting ([A] §5.1; docs/method.md §4).
#include <gtest/gtest.h>

#include <cmath>

#include "rope/rod/rod.h"
#include "tests/rope/rod/rod_test_util.h"

namespace rope {
namespace {

RodSettings cutSettings() {
  RodSettings settings;
  settings.restLength = 1.0;
  settings.linearDensity = 0.1;
  settings.youngsModulus = 1e7;
  settings.stiffnessDamping = 0.01;  // Rayleigh damping on K only: keeps momentum (free-fall check)
  settings.initialControlPoints = 15;  // 12 uniform spans: s = 0.5 is a knot
  settings.adaptive = false;
  return settings;
}

TEST(RodCut, PiecesCarryTheRightMassEnergyAndVelocities) {
  for (StretchingQuadrature quadrature : {StretchingQuadrature::kExact, StretchingQuadrature::kLockingFree}) {
  RodSettings settings = cutSettings();
  settings.stretchingQuadrature = quadrature;
  // Exact quadrature splits the stretching energy exactly; the locking-free rule samples the strain
  // differently next to the new ends (they become end spans with extra points), a quadrature-level
  // difference.
  const double stretchTolerance = quadrature == StretchingQuadrature::kExact ? 1e-9 : 2e-2;
  Rod rod = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(1, 0, 0));
  rod.pin(0.0);
  for (int i = 0; i < 60; ++i) ASSERT_TRUE(rod.step(1.0 / 240).ok);
  for (double s : {0.5, 0.3141}) {  // at a knot and inside a span
    const auto [left, right] = rod.cut(s);
    EXPECT_EQ(left.endParameter(), s);
    EXPECT_EQ(right.beginParameter(), s);
    EXPECT_NEAR(left.mass() + right.mass(), rod.mass(), 1e-14);
    EXPECT_NEAR(left.restLength(), s, 1e-13);
    EXPECT_NEAR(left.restLength() + right.restLength(), rod.restLength(), 1e-13);
    EXPECT_LT((left.momentum() + right.momentum() - rod.momentum()).norm(), 1e-14);
    EXPECT_NEAR(left.kineticEnergy() + right.kineticEnergy(), rod.kineticEnergy(), 1e-12 * rod.kineticEnergy());
    EXPECT_NEAR(left.stretchingEnergy() + right.stretchingEnergy(), rod.stretchingEnergy(),
                stretchTolerance * rod.stretchingEnergy());
    EXPECT_NEAR(left.bendingEnergy() + right.bendingEnergy(), rod.bendingEnergy(), 1e-9 * rod.bendingEnergy());
    EXPECT_NEAR(left.gravityEnergy() + right.gravityEnergy(), rod.gravityEnergy(), 1e-12);
    for (double t : {0.0, 0.5 * s, s}) {
      EXPECT_LT((left.position(t) - rod.position(t)).norm(), 1e-13);
      EXPECT_LT((left.velocity(t) - rod.velocity(t)).norm(), 1e-12);
    }
    for (double t : {s, 0.5 * (s + 1.0), 1.0}) {
      EXPECT_LT((right.position(t) - rod.position(t)).norm(), 1e-13);
      EXPECT_LT((right.velocity(t) - rod.velocity(t)).norm(), 1e-12);
    }
    EXPECT_EQ(left.pins().size(), 1u);
    EXPECT_TRUE(right.pins().empty());
  }
  }
}

TEST(RodCut, APieceBehavesExactlyLikeTheSamePieceSimulatedAlone) {
  const RodSettings settings = cutSettings();
  Rod rod = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(1, 0, 0));
  const int pinId = rod.pin(0.0);
  for (int i = 0; i < 90; ++i) ASSERT_TRUE(rod.step(1.0 / 240).ok);
  auto [left, right] = rod.cut(0.5);
  ASSERT_EQ(left.pins().size(), 1u);
  EXPECT_EQ(left.pins()[0].id, pinId);
  // The same piece made from scratch: a straight 0.5 m rope with 9 control points, then given the
  // piece's current positions and velocities.
  RodSettings alone = settings;
  alone.restLength = 0.5;
  alone.initialControlPoints = 9;
  Rod fresh = Rod::fromSegment(alone, Vec3(0, 0, 0), Vec3(0.5, 0, 0));
  ASSERT_EQ(fresh.controlPointCount(), left.controlPointCount());
  for (int i = 0; i < fresh.knots().size(); ++i) ASSERT_NEAR(fresh.knots()[i], left.knots()[i], 1e-15);
  fresh.setControlPoints(left.controlPoints());
  fresh.setVelocities(left.velocities());
  fresh.pin(0.0);
  EXPECT_NEAR(fresh.mass(), left.mass(), 1e-15);
  const Vec3 rightMomentum = right.momentum();
  for (int i = 0; i < 480; ++i) {
    ASSERT_TRUE(left.step(1.0 / 240).ok);
    ASSERT_TRUE(fresh.step(1.0 / 240).ok);
    ASSERT_TRUE(right.step(1.0 / 240).ok);
  }
  double difference = 0.0;
  for (int i = 0; i < fresh.controlPointCount(); ++i)
    difference = std::max(difference, (fresh.controlPoints()[static_cast<size_t>(i)] -
                                       left.controlPoints()[static_cast<size_t>(i)]).norm());
  EXPECT_LT(difference, 1e-9);
  // The free right piece falls freely: its momentum grows by m g t exactly.
  EXPECT_LT((right.momentum() - (rightMomentum + right.mass() * settings.gravity * 2.0)).norm(), 1e-10);
  std::printf("[cut] piece vs same piece alone after 2 s: max control point difference %.3e m\n", difference);
}

}  // namespace
}  // namespace rope
