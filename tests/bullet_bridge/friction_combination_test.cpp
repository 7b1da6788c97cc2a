// SPDX-License-Identifier: MIT
// Friction the Bullet way (bullet_bridge/friction_combination.h): the rope-body coefficient is the
// rope's times the body's getFriction(), a RopeWorld combiner replaces the rule, and a bad combiner
// fails the rope's substep without escaping stepSimulation.
#include "bullet_bridge/friction_combination.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <cstdio>
#include <limits>

#include "bullet_bridge/rope_world.h"
#include "demos/scenes/physics_world.h"

namespace rope::bullet {
namespace {

constexpr double kStep = 1.0 / 240.0;
constexpr double kSlope = 20.0 * 3.14159265358979323846 / 180.0;  // tan = 0.364

struct Ramp {
  demos::PhysicsWorld physics;
  btRigidBody* ramp = nullptr;
  std::unique_ptr<RopeObject> rope;
  Vec3 downhill;  // unit, along the slope

  explicit Ramp(double bodyFriction, double ropeFriction = BulletRopeSettings().friction) {
    btTransform transform;
    transform.setIdentity();
    transform.setRotation(btQuaternion(btVector3(0, 0, 1), btScalar(-kSlope)));
    ramp = physics.addBox(btVector3(2, btScalar(0.1), 1), 0.0, transform);
    ramp->setFriction(static_cast<btScalar>(bodyFriction));
    downhill = Vec3(std::cos(kSlope), -std::sin(kSlope), 0.0);
    const Vec3 up(std::sin(kSlope), std::cos(kSlope), 0.0);  // the face's normal
    RodSettings rod;
    rod.restLength = 0.6;
    const Vec3 centre = (0.1 + rod.radius) * up;  // on the top face
    BulletRopeSettings bridge;
    bridge.friction = ropeFriction;
    rope = std::make_unique<RopeObject>(Rod::fromSegment(rod, centre - 0.3 * downhill, centre + 0.3 * downhill), bridge);
    physics.ropes().addRope(*rope);
  }
  // Distance the rope's middle moved down the slope in `seconds`.
  double slide(double seconds) {
    const Vec3 start = rope->rod().position(0.3);
    const int steps = static_cast<int>(std::lround(seconds / kStep));
    for (int i = 0; i < steps; ++i) physics.world().stepSimulation(btScalar(kStep), 1, btScalar(kStep));
    return (rope->rod().position(0.3) - start).dot(downhill);
  }
};

// Coulomb's law for the rope as a whole: it holds while tan(slope) <= mu and otherwise slides
// (1/2) g (sin - mu cos) t^2 down the slope.
double coulombSlide(double mu, double t) {
  return std::max(0.0, 0.5 * 9.81 * (std::sin(kSlope) - mu * std::cos(kSlope)) * t * t);
}

TEST(FrictionCombination, IsBulletsClampedProduct) {
  EXPECT_EQ(combinedFriction(1.0, 0.5), 0.5);
  EXPECT_EQ(combinedFriction(0.3, 0.0), 0.0);
  EXPECT_EQ(combinedFriction(4.0, 5.0), kMaxCombinedFriction);
  EXPECT_EQ(BulletRopeSettings().friction, 1.0);  // against a default Bullet body (0.5): 0.5
}

// The same rope (friction 1) on a 20 degree ramp: a ramp of friction 1 holds it (mu = 1), a default
// ramp too (0.5 > tan 20 = 0.364), one of 0.2 lets it slide at Coulomb's rate for mu = 0.2, and an
// ice ramp (friction 0) lets it slide off freely.
TEST(FrictionCombination, BodyFrictionDecidesWhetherTheRopeSlidesOffARamp) {
  const double t = 1.0;
  struct Case {
    double bodyFriction;
    double expected;  // m down the slope after t
  };
  for (const Case c : {Case{1.0, 0.0}, Case{0.5, 0.0}, Case{0.2, coulombSlide(0.2, t)}, Case{0.0, coulombSlide(0.0, t)}}) {
    Ramp ramp(c.bodyFriction);
    const double slid = ramp.slide(t);
    ASSERT_TRUE(ramp.rope->lastStep().ok);
    if (c.expected == 0.0) {
      EXPECT_LT(std::abs(slid), 1e-4) << "body friction " << c.bodyFriction;  // held (sticking springs: um)
    } else {
      // The rope starts resting on the ramp; within 3 % of the rigid Coulomb slide.
      EXPECT_NEAR(slid, c.expected, 0.03 * c.expected) << "body friction " << c.bodyFriction;
    }
    std::printf("ramp friction %.1f: slid %.5f m in %.1f s (Coulomb %.5f m)\n", c.bodyFriction, slid, t, c.expected);
  }
}

// A combiner replaces the product: the minimum of the two lets the ramp of friction 0.2 decide
// alone (slides), and a constant 1 makes even the ice ramp hold.
TEST(FrictionCombination, WorldCombinerReplacesTheProduct) {
  {
    Ramp ramp(0.0);
    ramp.physics.ropes().setBodyFrictionCombiner([](const RopeObject&, const btCollisionObject&) { return 1.0; });
    EXPECT_LT(std::abs(ramp.slide(1.0)), 1e-4);
  }
  {
    // A ramp of friction 0.5 and a rope of 0.2: the minimum (0.2) lets it slide.
    Ramp ramp(0.5, 0.2);
    ramp.physics.ropes().setBodyFrictionCombiner([](const RopeObject& rope, const btCollisionObject& body) {
      return std::min(rope.settings().friction, static_cast<double>(body.getFriction()));
    });
    const double slid = ramp.slide(1.0);
    EXPECT_NEAR(slid, coulombSlide(0.2, 1.0), 0.03 * coulombSlide(0.2, 1.0));
  }
}

// A combiner that returns NaN fails the substeps of the ropes touching a body: counted, the rope
// keeps its state, nothing escapes stepSimulation; restoring the default makes it step again.
TEST(FrictionCombination, BadCombinerFailsTheSubstepAndIsCounted) {
  Ramp ramp(0.5);
  ramp.slide(0.05);  // resting on the ramp
  ramp.physics.ropes().setBodyFrictionCombiner(
      [](const RopeObject&, const btCollisionObject&) { return std::numeric_limits<double>::quiet_NaN(); });
  const Vec3 before = ramp.rope->rod().position(0.3);
  EXPECT_NO_THROW(ramp.slide(0.1));

  EXPECT_FALSE(ramp.rope->lastStep().ok);
  EXPECT_GT(ramp.rope->warnings().exceptions, 0);
  EXPECT_NE(ramp.rope->lastError().find("friction combiner"), std::string::npos) << ramp.rope->lastError();
  EXPECT_EQ(ramp.rope->rod().position(0.3), before);
  ramp.physics.ropes().setBodyFrictionCombiner(nullptr);
  ramp.slide(0.05);
  EXPECT_TRUE(ramp.rope->lastStep().ok);
}

}  // namespace
}  // namespace rope::bullet
