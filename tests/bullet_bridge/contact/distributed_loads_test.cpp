// SPDX-License-Identifier: MIT
// Distributed loads on a rope in a Bullet world (bullet_bridge/contact/distributed_loads.h): a force per
// metre integrated consistently, and aerodynamic drag against analytic terminal velocities.
#include "bullet_bridge/contact/distributed_loads.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "bullet_bridge/rope_world.h"
#include "demos/scenes/physics_world.h"
#include "rope/common/error.h"

namespace rope::bullet {
namespace {

constexpr double kStep = 1.0 / 240.0;

void stepWorld(btDiscreteDynamicsWorld& world, int steps) {
  for (int i = 0; i < steps; ++i) world.stepSimulation(btScalar(kStep), 1, btScalar(kStep));
}

Vec3 centreOfMassVelocity(const Rod& rod) { return rod.momentum() / rod.mass(); }

// A force per metre over [s0, s1] changes the momentum by exactly q (s1 - s0) h in one substep
// (the basis functions sum to one, so the consistent forces sum to the load), and acts once.
TEST(DistributedForce, ChangesMomentumByTheIntegralOfTheLoad) {
  demos::PhysicsWorld physics(btVector3(0, 0, 0));
  RodSettings fixedKnots;
  fixedKnots.adaptive = false;  // knot removal may change a moving rope's momentum (removal bound)
  RopeObject rope(Rod::fromSegment(fixedKnots, Vec3(0, 1, 0), Vec3(1, 1, 0)));
  physics.ropes().addRope(rope);
  const Vec3 q(0.3, -1.2, 0.5);  // N/m
  rope.applyDistributedForce(0.0, 1.0, btVector3(0.3, -1.2, 0.5));
  stepWorld(physics.world(), 1);
  Vec3 expected = q * 1.0 * kStep;
  EXPECT_LT((rope.rod().momentum() - expected).norm(), 1e-12 * expected.norm());
  // Over a stretch that starts and ends inside knot spans.
  rope.applyDistributedForce(0.23, 0.71, btVector3(0.3, -1.2, 0.5));
  stepWorld(physics.world(), 1);
  expected += q * 0.48 * kStep;
  EXPECT_LT((rope.rod().momentum() - expected).norm(), 1e-12 * expected.norm());
  stepWorld(physics.world(), 1);  // acted once
  EXPECT_LT((rope.rod().momentum() - expected).norm(), 1e-12 * expected.norm());
}

// The consistent generalised forces are the limit of many point forces: a load over [0.37, 0.93]
// moves every point of the rope as 2000 point forces q ds at the midpoints of equal pieces do (the
// midpoint rule's error, O(ds^2), is the only difference).
TEST(DistributedForce, EqualsTheLimitOfPointForces) {
  demos::PhysicsWorld physics(btVector3(0, 0, 0));
  RodSettings fixedKnots;
  fixedKnots.adaptive = false;
  RopeObject spread(Rod::fromSegment(fixedKnots, Vec3(0, 1, 0), Vec3(1, 1, 0)));
  RopeObject points(Rod::fromSegment(fixedKnots, Vec3(0, 1, 5), Vec3(1, 1, 5)));
  physics.ropes().addRope(spread);
  physics.ropes().addRope(points);
  const btVector3 q(0.4, 2.0, -1.0);
  spread.applyDistributedForce(0.37, 0.93, q);
  const int pieces = 2000;
  const double ds = (0.93 - 0.37) / pieces;
  for (int i = 0; i < pieces; ++i) points.applyForce(0.37 + (i + 0.5) * ds, q * btScalar(ds));
  stepWorld(physics.world(), 1);
  double worst = 0.0, largest = 0.0;
  for (int i = 0; i <= 20; ++i) {
    const double s = i / 20.0;
    worst = std::max(worst, (spread.rod().velocity(s) - points.rod().velocity(s)).norm());
    largest = std::max(largest, spread.rod().velocity(s).norm());
  }
  EXPECT_GT(largest, 1e-3);
  EXPECT_LT(worst, 1e-6 * largest);
}

struct Fall {
  double speed = 0.0;      // m/s, downward speed of the centre of mass at the end
  double drift = 0.0;      // m/s, largest change of that speed over the last second
};

// A 1 m rope released from rest, horizontal or vertical, in air without bodies.
Fall fall(const Vec3& direction, double seconds, const BulletRopeSettings& settings) {
  demos::PhysicsWorld physics;  // gravity (0, -9.81, 0)
  RodSettings rod;              // 5 mm nylon, 0.0903 kg/m
  RopeObject rope(Rod::fromSegment(rod, Vec3(0, 100, 0), Vec3(0, 100, 0) + direction), settings);
  physics.ropes().addRope(rope);
  const int steps = static_cast<int>(std::lround(seconds / kStep));
  Fall result;
  double lastSecond = 0.0;
  for (int i = 0; i < steps; ++i) {
    stepWorld(physics.world(), 1);
    EXPECT_TRUE(rope.lastStep().ok);
    if (i == steps - 241) lastSecond = -centreOfMassVelocity(rope.rod()).y();
  }
  result.speed = -centreOfMassVelocity(rope.rod()).y();
  result.drift = std::abs(result.speed - lastSecond);
  return result;
}

// Terminal velocity of a falling rope: weight per metre mu g = c v^2, c = rho d C_n / 2 falling
// across (horizontal rope), c = rho pi d C_t / 2 falling along itself (vertical rope).
TEST(Drag, FallingRopeReachesTheAnalyticTerminalVelocity) {
  BulletRopeSettings air;
  air.fluidDensity = 1.2;
  const RodSettings rod;
  const double weight = rod.effectiveLinearDensity() * 9.81;  // N/m
  const double d = 2.0 * rod.radius;
  const double across = std::sqrt(weight / (0.5 * air.fluidDensity * d * air.normalDragCoefficient));
  // Along: a denser fluid keeps the terminal speed (and the fall) short.
  BulletRopeSettings water = air;
  water.fluidDensity = 1000.0;
  const double along = std::sqrt(weight / (0.5 * water.fluidDensity * 3.14159265358979323846 * d *
                                           water.tangentialDragCoefficient));
  const Fall horizontal = fall(Vec3(1, 0, 0), 6.0, air);
  const Fall vertical = fall(Vec3(0, -1, 0), 6.0, water);
  const double errorAcross = std::abs(horizontal.speed - across) / across;
  const double errorAlong = std::abs(vertical.speed - along) / along;
  EXPECT_LT(errorAcross, 0.02) << horizontal.speed << " m/s against " << across;
  EXPECT_LT(errorAlong, 0.02) << vertical.speed << " m/s against " << along;
  EXPECT_LT(horizontal.drift, 1e-3 * across);  // terminal: no longer accelerating
  EXPECT_LT(vertical.drift, 1e-3 * along);
  RecordProperty("terminal_velocity_error_across", formatValue(errorAcross));
  RecordProperty("terminal_velocity_error_along", formatValue(errorAlong));
  std::printf("terminal velocity across %.5f m/s (analytic %.5f, error %.2e), along %.5f m/s (analytic %.5f, "
              "error %.2e)\n",
              horizontal.speed, across, errorAcross, vertical.speed, along, errorAlong);
}

// Drag is relative to the wind: a weightless rope at rest in a 3 m/s wind is carried towards the
// wind's speed and never beyond it; one already moving with the wind feels nothing.
TEST(Drag, ActsOnTheVelocityRelativeToTheWind) {
  BulletRopeSettings windy;
  windy.fluidDensity = 1.2;
  windy.windVelocity = btVector3(3, 0, 0);
  demos::PhysicsWorld physics(btVector3(0, 0, 0));
  RodSettings fixedKnots;
  fixedKnots.adaptive = false;
  RopeObject still(Rod::fromSegment(fixedKnots, Vec3(0, 1, 0), Vec3(0, 1, 1)), windy);
  RopeObject carried(Rod::fromSegment(fixedKnots, Vec3(0, 3, 0), Vec3(0, 3, 1)), windy);
  carried.rod().setVelocities(PointList(static_cast<std::size_t>(carried.rod().controlPointCount()), Vec3(3, 0, 0)));
  physics.ropes().addRope(still);
  physics.ropes().addRope(carried);
  double previous = 0.0;
  for (int i = 0; i < 2400; ++i) {
    stepWorld(physics.world(), 1);
    const double vx = centreOfMassVelocity(still.rod()).x();
    ASSERT_GE(vx, previous - 1e-12);  // accelerates monotonically ...
    ASSERT_LT(vx, 3.0);               // ... and never overtakes the wind (implicit drag)
    previous = vx;
  }
  EXPECT_GT(previous, 2.0);
  // Round-off only (measured 5e-11 m/s after 10 s; drag on the absolute speed would have slowed it
  // by metres per second).
  EXPECT_LT((centreOfMassVelocity(carried.rod()) - Vec3(3, 0, 0)).norm(), 1e-9);
}

// Drag off by default: a rope falls exactly as without it.
TEST(Drag, OffByDefault) {
  EXPECT_EQ(BulletRopeSettings().fluidDensity, 0.0);
  const Fall free = fall(Vec3(1, 0, 0), 0.5, BulletRopeSettings());
  EXPECT_NEAR(free.speed, 9.81 * 0.5, 1e-9);
}

TEST(DistributedForce, BadInputNamesTheArgumentAndQueuesNothing) {
  demos::PhysicsWorld physics(btVector3(0, 0, 0));
  RodSettings fixedKnots;
  fixedKnots.adaptive = false;
  RopeObject rope(Rod::fromSegment(fixedKnots, Vec3(0, 1, 0), Vec3(1, 1, 0)));
  physics.ropes().addRope(rope);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const struct {
    const char* name;
    double s0, s1;
    btVector3 q;
  } cases[] = {{"s0", nan, 1.0, btVector3(1, 0, 0)},   {"s1", 0.0, nan, btVector3(1, 0, 0)},
               {"s0", -0.1, 1.0, btVector3(1, 0, 0)},  {"s1", 0.0, 1.5, btVector3(1, 0, 0)},
               {"s1", 0.5, 0.5, btVector3(1, 0, 0)},   {"s1", 0.6, 0.4, btVector3(1, 0, 0)},
               {"forcePerLength[1]", 0.0, 1.0, btVector3(0, btScalar(nan), 0)}};
  for (const auto& c : cases) {
    try {
      rope.applyDistributedForce(c.s0, c.s1, c.q);
      ADD_FAILURE() << c.name << " accepted";
    } catch (const InvalidArgument& error) {
      EXPECT_EQ(error.parameter(), c.name) << error.what();
    }
  }
  stepWorld(physics.world(), 1);
  // Nothing was queued (one of those loads would have given 4e-3 N s; round-off of the rope's
  // unstretched state gives 1e-15).
  EXPECT_LT(rope.rod().momentum().norm(), 1e-13);
  BulletRopeSettings bad;
  bad.windVelocity = btVector3(0, 0, btScalar(std::numeric_limits<double>::infinity()));
  EXPECT_THROW(RopeObject(Rod::fromSegment(RodSettings(), Vec3(0, 1, 0), Vec3(1, 1, 0)), bad), InvalidArgument);
}

}  // namespace
}  // namespace rope::bullet
