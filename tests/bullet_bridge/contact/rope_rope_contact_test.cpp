// SPDX-License-Identifier: MIT
// Scenario tests of rope-rope and self-contact (bullet_bridge/contact/rope_rope_contact.h) and of cutting a
// rope in a Bullet world (RopeObject::cut).
#include "bullet_bridge/contact/rope_rope_contact.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "bullet_bridge/rope_world.h"
#include "demos/scenes/knot_scene.h"
#include "demos/scenes/physics_world.h"
#include "rope/common/error.h"

namespace rope::bullet {
namespace {

constexpr double kStep = 1.0 / 240.0;

RodSettings cord(const Vec3& gravity = Vec3(0, -9.81, 0)) {
  RodSettings rod = demos::KnotSceneSettings::defaultRod();
  rod.gravity = gravity;
  return rod;
}

BulletRopeSettings cordContact() { return demos::KnotSceneSettings::defaultBridge(); }

void step(demos::PhysicsWorld& physics) { physics.world().stepSimulation(btScalar(kStep), 1, btScalar(kStep)); }

double deepestRopeContact(const demos::PhysicsWorld& physics) { return physics.ropes().lastReport().maxSelfOverlap(); }

// Height of a rope where it crosses the other one, i.e. at its point nearest to the vertical line
// x = z = 0 (the lower rope lies along x, the upper one along z).
double heightAtCrossing(const Rod& a) {
  double best = std::numeric_limits<double>::infinity(), y = 0.0;
  for (int i = 0; i <= 400; ++i) {
    const double s = std::min(a.endParameter(), a.beginParameter() + (a.endParameter() - a.beginParameter()) * i / 400.0);
    const Vec3 p = a.position(s);
    if (std::hypot(p.x(), p.z()) < best) best = std::hypot(p.x(), p.z()), y = p.y();
  }
  return y;
}

struct CrossingRopes {
  demos::PhysicsWorld physics;
  std::unique_ptr<RopeObject> lower, upper;
  // lower: along x, pinned at both ends at height 0.5; upper: along z, `gap` above it, moving down at speed.
  CrossingRopes(double gap, double speed, const Vec3& gravity = Vec3(0, -9.81, 0), bool pinLower = true)
      : physics(btVector3(btScalar(gravity.x()), btScalar(gravity.y()), btScalar(gravity.z()))) {
    RodSettings rod = cord(gravity);
    // Without gravity the ropes are free: no drag either, so that momentum is conserved exactly.
    if (gravity.isZero()) rod.massDamping = 0.0;
    rod.restLength = 1.0;
    lower = std::make_unique<RopeObject>(Rod::fromSegment(rod, Vec3(-0.5, 0.5, 0), Vec3(0.5, 0.5, 0)), cordContact());
    rod.restLength = 0.6;
    const double y = 0.5 + 2.0 * rod.radius + gap;
    Rod falling = Rod::fromSegment(rod, Vec3(0, y, -0.3), Vec3(0, y, 0.3));
    falling.setVelocities(PointList(static_cast<size_t>(falling.controlPointCount()), Vec3(0, -speed, 0)));
    upper = std::make_unique<RopeObject>(std::move(falling), cordContact());
    physics.ropes().addRope(*lower);
    physics.ropes().addRope(*upper);
    if (pinLower) {
      lower->attachToPoint(lower->rod().beginParameter(), btVector3(-0.5, 0.5, 0));
      lower->attachToPoint(lower->rod().endParameter(), btVector3(0.5, 0.5, 0));
    }
  }
};

TEST(RopeRopeContactScenario, RopeDroppedAcrossAnotherDrapesOverIt) {
  CrossingRopes scene(0.05, 0.0);
  const double diameter = 2.0 * scene.lower->rod().settings().radius;
  double worst = 0.0;
  for (int i = 0; i < 480; ++i) {
    step(scene.physics);
    worst = std::max(worst, deepestRopeContact(scene.physics));
    ASSERT_TRUE(scene.upper->lastStep().ok && scene.lower->lastStep().ok);
  }
  EXPECT_LT(worst, 0.2 * diameter);
  // Hanging over the lower rope: its crossing point sits one diameter above the lower rope's centre.
  const double lowerY = heightAtCrossing(scene.lower->rod());  // the lower rope at z = 0 (along x)
  EXPECT_NEAR(heightAtCrossing(scene.upper->rod()) - lowerY, diameter, 0.15 * diameter);
  EXPECT_GT(scene.upper->lastStep().ropeContacts, 0);
  // Both ends of the draped rope hang below the crossing.
  EXPECT_LT(scene.upper->rod().position(scene.upper->rod().beginParameter()).y(), lowerY - 0.1);
  EXPECT_LT(scene.upper->rod().position(scene.upper->rod().endParameter()).y(), lowerY - 0.1);
}

TEST(RopeRopeContactScenario, FastRopeDoesNotPassThroughAnotherRope) {
  for (const double speed : {5.0, 15.0}) {
    CrossingRopes scene(0.02, speed);
    for (int i = 0; i < 60; ++i) step(scene.physics);
    EXPECT_GT(heightAtCrossing(scene.upper->rod()), heightAtCrossing(scene.lower->rod())) << speed << " m/s";
  }
}

TEST(RopeRopeContactScenario, FreeRopesCollidingConserveLinearMomentum) {
  CrossingRopes scene(0.01, 2.0, Vec3::Zero(), false);
  const auto momentum = [&scene]() -> Vec3 { return scene.lower->rod().momentum() + scene.upper->rod().momentum(); };
  const Vec3 initial = momentum();
  int contactSteps = 0, removals = 0;
  double worst = 0.0;
  for (int i = 0; i < 120; ++i) {
    step(scene.physics);
    if (scene.upper->lastStep().ropeContacts > 0) ++contactSteps;
    removals += scene.upper->lastStep().removals + scene.lower->lastStep().removals;
    worst = std::max(worst, (momentum() - initial).norm() / initial.norm());
  }
  // Default adaptivity: measured 3.5e-13 relative with 24 knot removals (of knots the straight,
  // uniformly moving parts no longer need, which the removal's velocity check finds exact). The
  // README's figure is 1e-12.
  EXPECT_GT(removals, 0);
  EXPECT_LT(worst, 1e-12);
  std::printf("free ropes: worst relative momentum drift %.3g, %d removals, %d contact steps\n", worst, removals,
              contactSteps);
  EXPECT_GT(contactSteps, 3);
  // The impact moved the lower rope: momentum really went across.
  EXPECT_GT(scene.lower->rod().momentum().norm(), 0.2 * initial.norm());
}

// Two free ropes meeting side by side (the upper one parallel to the lower, 1 cm above it, at 2 m/s):
// a distributed contact (docs/method.md §12), sampled along the touching stretch, whose samples
// conserve momentum as point contacts do.
TEST(RopeRopeContactScenario, ParallelRopesMeetInADistributedContactThatConservesMomentum) {
  demos::PhysicsWorld physics(btVector3(0, 0, 0));
  RodSettings rod = cord(Vec3::Zero());
  rod.massDamping = 0.0;
  rod.restLength = 1.0;
  RopeObject lower(Rod::fromSegment(rod, Vec3(-0.5, 0.5, 0), Vec3(0.5, 0.5, 0)), cordContact());
  rod.restLength = 0.6;
  const double y = 0.5 + 2.0 * rod.radius + 0.01;
  Rod falling = Rod::fromSegment(rod, Vec3(-0.3, y, 0), Vec3(0.3, y, 0));
  falling.setVelocities(PointList(static_cast<size_t>(falling.controlPointCount()), Vec3(0, -2.0, 0)));
  RopeObject upper(std::move(falling), cordContact());
  physics.ropes().addRope(lower);
  physics.ropes().addRope(upper);
  const auto momentum = [&]() -> Vec3 { return lower.rod().momentum() + upper.rod().momentum(); };
  const Vec3 initial = momentum();
  int sampledSteps = 0;
  double worst = 0.0, longest = 0.0;
  for (int i = 0; i < 120; ++i) {
    step(physics);
    double sampled = 0.0;  // m of rope in acting distributed contact this substep
    for (const RopePairContactRecord& record : physics.ropes().lastReport().ropeContacts) {
      if (record.active) sampled += record.weight;
    }
    if (sampled > 0.0) ++sampledSteps;
    longest = std::max(longest, sampled);
    worst = std::max(worst, (momentum() - initial).norm() / initial.norm());
  }
  std::printf("parallel ropes: %d steps in distributed contact, longest %.3f m, worst relative momentum drift %.3g\n",
              sampledSteps, longest, worst);
  EXPECT_GT(sampledSteps, 3);
  // Most of the upper rope's 0.6 m lands along the lower one at once.
  EXPECT_GT(longest, 0.3);
  EXPECT_LT(worst, 1e-12);
  EXPECT_GT(lower.rod().momentum().norm(), 0.2 * initial.norm());
  physics.ropes().removeRope(upper);
  physics.ropes().removeRope(lower);
}

// A removed rope may be destroyed next: the last report keeps no rope-rope record pointing at it.
TEST(RopeRopeContactScenario, RemovingARopeClearsTheRecordsThatNameIt) {
  CrossingRopes scene(0.02, 3.0);
  bool touched = false;
  for (int i = 0; i < 120 && !touched; ++i) {
    step(scene.physics);
    touched = !scene.physics.ropes().lastReport().ropeContacts.empty();
  }
  ASSERT_TRUE(touched);
  scene.physics.ropes().removeRope(*scene.upper);
  for (const RopePairContactRecord& record : scene.physics.ropes().lastReport().ropeContacts) {
    EXPECT_NE(record.ropeA, scene.upper.get());
    EXPECT_NE(record.ropeB, scene.upper.get());
  }
}

TEST(RopeRopeContactScenario, TwinRunsAreBitwiseIdentical) {
  CrossingRopes a(0.02, 3.0), b(0.02, 3.0);
  for (int i = 0; i < 120; ++i) {
    step(a.physics);
    step(b.physics);
    for (const auto& [x, y] : {std::pair{a.upper.get(), b.upper.get()}, std::pair{a.lower.get(), b.lower.get()}}) {
      ASSERT_EQ(x->rod().knots().values(), y->rod().knots().values()) << i;
      for (int k = 0; k < x->rod().controlPointCount(); ++k) {
        ASSERT_EQ(x->rod().controlPoints()[static_cast<size_t>(k)], y->rod().controlPoints()[static_cast<size_t>(k)]) << i;
      }
    }
  }
}

TEST(RopeRopeContactScenario, BroadphaseMaskAndSelfContactSwitchTurnContactOff) {
  // A rope whose mask leaves out the rope group falls through the other one.
  CrossingRopes masked(0.02, 1.0);
  masked.physics.ropes().removeRope(*masked.upper);
  BulletRopeSettings settings = cordContact();
  settings.collisionMask = ~settings.collisionGroup;
  RopeObject ghost(masked.upper->rod(), settings);
  masked.physics.ropes().addRope(ghost);
  for (int i = 0; i < 120; ++i) {
    step(masked.physics);
    ASSERT_TRUE(masked.physics.ropes().lastReport().ropeContacts.empty());
  }
  EXPECT_LT(heightAtCrossing(ghost.rod()), heightAtCrossing(masked.lower->rod()) - 0.05);

  // The knot scene without self-contact reports none, and its strands pass through each other.
  demos::KnotSceneSettings knot;
  knot.bridge.selfContact = false;
  demos::KnotScene scene(knot);
  for (int i = 0; i < 120; ++i) {
    scene.step();
    ASSERT_TRUE(scene.physics().ropes().lastReport().ropeContacts.empty());
  }
}

TEST(RopeRopeContactScenario, RestingStraightRopeDoesNotTouchItself) {
  // Neighbouring capsules always overlap; the exclusion along the rest curve keeps them out.
  demos::PhysicsWorld physics;
  physics.addGround(0.0);
  RodSettings rod = cord();
  rod.restLength = 1.0;
  RopeObject rope(Rod::fromSegment(rod, Vec3(-0.5, 0.3, 0), Vec3(0.5, 0.3, 0)), cordContact());
  physics.ropes().addRope(rope);
  for (int i = 0; i < 240; ++i) {
    step(physics);
    ASSERT_TRUE(physics.ropes().lastReport().ropeContacts.empty()) << "step " << i;
  }
}

TEST(RopeRopeContact, SettingsAreValidated) {
  BulletRopeSettings settings;
  settings.selfContactExclusion = -0.5;
  try {
    settings.validate();
    ADD_FAILURE() << "accepted a negative exclusion";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.parameter(), "settings.selfContactExclusion");
  }
  settings.selfContactExclusion = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(settings.validate(), InvalidArgument);
  settings.selfContactExclusion = BulletRopeSettings::kDerivedExclusion;
  EXPECT_NO_THROW(settings.validate());
  EXPECT_DOUBLE_EQ(settings.effectiveSelfContactExclusion(0.005), 0.02);
}

// ---- cutting ----

TEST(RopeObjectCut, SplitsStateAndAttachmentsExactlyAndAddsThePieceToTheWorld) {
  demos::PhysicsWorld physics;
  btRigidBody* box = physics.addBox(btVector3(0.05, 0.05, 0.05), 1.0, btVector3(0, 0.95, 0));
  RodSettings rod = cord();
  rod.restLength = 1.0;
  RopeObject rope(Rod::fromSegment(rod, Vec3(0, 2, 0), Vec3(0, 1, 0)), cordContact());
  physics.ropes().addRope(rope);
  const int top = rope.attachToPoint(0.0, btVector3(0, 2, 0));
  const int bottom = rope.attachToBody(1.0, *box, btVector3(0, 0.05, 0));
  for (int i = 0; i < 60; ++i) step(physics);
  const double mass = rope.rod().mass();
  const Vec3 momentum = rope.rod().momentum();
  const double kinetic = rope.rod().kineticEnergy();
  std::vector<Vec3> positions, velocities;
  for (int k = 0; k <= 20; ++k) {
    positions.push_back(rope.rod().position(0.05 * k));
    velocities.push_back(rope.rod().velocity(0.05 * k));
  }

  std::unique_ptr<RopeObject> piece = rope.cut(0.4);
  EXPECT_EQ(rope.rod().endParameter(), 0.4);
  EXPECT_EQ(piece->rod().beginParameter(), 0.4);
  EXPECT_NEAR(rope.rod().mass() + piece->rod().mass(), mass, 1e-15);
  EXPECT_LT((rope.rod().momentum() + piece->rod().momentum() - momentum).norm(), 1e-15);
  // The state is split exactly: the two curves and their velocity fields are the old ones on either
  // side of the cut, so the kinetic energy is kept to rounding (measured 1.7e-21 J of 1.0e-5 J). (The
  // stretching energy is not compared: the default locking-free rule's quadrature points move with the
  // knots the cut inserts, docs/method.md §7, by 7e-9 to 5e-8 of it here.)
  for (int k = 0; k <= 20; ++k) {
    const Rod& side = 0.05 * k <= 0.4 ? rope.rod() : piece->rod();
    EXPECT_LT((side.position(0.05 * k) - positions[static_cast<size_t>(k)]).norm(), 1e-14) << 0.05 * k;
    EXPECT_LT((side.velocity(0.05 * k) - velocities[static_cast<size_t>(k)]).norm(), 1e-14) << 0.05 * k;
  }
  EXPECT_NEAR(rope.rod().kineticEnergy() + piece->rod().kineticEnergy(), kinetic, 1e-12 * (1.0 + kinetic));
  ASSERT_EQ(rope.attachments().size(), 1u);
  EXPECT_EQ(rope.attachments()[0].id, top);
  ASSERT_EQ(piece->attachments().size(), 1u);
  EXPECT_EQ(piece->attachments()[0].id, bottom);
  EXPECT_EQ(piece->world(), rope.world());
  EXPECT_TRUE(physics.ropes().contains(*piece));
  ASSERT_EQ(rope.cutPartners().size(), 1u);
  EXPECT_EQ(rope.cutPartners()[0].rope, piece.get());
  for (int i = 0; i < 60; ++i) step(physics);
  EXPECT_TRUE(physics.ropes().lastReport().ropeContacts.empty());  // the cut ends do not push apart
  piece.reset();  // destroying a piece leaves its world and unlinks it
  EXPECT_TRUE(rope.cutPartners().empty());
  EXPECT_EQ(physics.ropes().ropes().size(), 1u);
}

TEST(RopeObjectCut, BadParameterThrowsAndChangesNothing) {
  demos::PhysicsWorld physics;
  RodSettings rod = cord();
  rod.restLength = 1.0;
  RopeObject rope(Rod::fromSegment(rod, Vec3(0, 2, 0), Vec3(0, 1, 0)), cordContact());
  physics.ropes().addRope(rope);
  rope.attachToPoint(0.5, btVector3(0, 1.5, 0));
  const PointList before = rope.rod().controlPoints();
  for (const double s : {0.0, 1.0, -0.1, 0.5, std::numeric_limits<double>::quiet_NaN()}) {
    try {
      rope.cut(s);
      ADD_FAILURE() << "cut at " << s;
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.parameter(), "s");
    }
  }
  EXPECT_EQ(rope.rod().controlPoints(), before);
  EXPECT_EQ(physics.ropes().ropes().size(), 1u);
  EXPECT_TRUE(rope.cutPartners().empty());
}

}  // namespace
}  // namespace rope::bullet
