// SPDX-License-Identifier: MIT
// Nothing escapes btDiscreteDynamicsWorld::stepSimulation (issue 17): every failure inside a rope's
// substep is injected here and must come back as a counted, reported failure, with the rope keeping
// its last good state and the world and the other ropes going on.
//   - an attached body whose linear or angular velocity is NaN (was: InvalidArgument("force[0]")
//     out of every step);
//   - a substep with h < 0, NaN or infinite (was: InvalidArgument("h") from the action);
//   - an exception from the narrowphase (a user's concave shape throwing; the contact path caught
//     only InvalidArgument) of a dynamic or a kinematic rope, from the substep callback, and from a
//     kinematic rope's followPath;
//   - a step that is finite but garbage: rod.step(1.0) on a rope hanging from one end, released
//     horizontal (was: ok at 3.75 times the rest length) fails by Rod::kMaxStepStretch and keeps the rod;
//   - a rope that keeps failing (a pin target 100 m away: every step would overstretch it) is put to
//     rest after RopeObject::kFailuresBeforeRest failures, frozen and still colliding: a box dropped
//     on it stays on top, and wake() lets it step again.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "bullet_bridge/kinematic_rope.h"
#include "bullet_bridge/rope_world.h"
#include "demos/scenes/drape_scene.h"
#include "reliability/reliability_support.h"
#include "rope/tractrix/tractrix_rope.h"
#include "support/fp_exceptions.h"

namespace rope::bullet {
namespace {

using test::ActionWorld;
using test::rodState;
using test::sameBits;

constexpr double kStep = 1.0 / 240.0;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

RodSettings limpRope() { return demos::DrapeSceneSettings::defaultRod(); }

bool finiteRod(const Rod& rod) {
  for (const Vec3& p : rod.controlPoints())
    if (!p.allFinite()) return false;
  for (const Vec3& v : rod.velocities())
    if (!v.allFinite()) return false;
  return true;
}

// A rope hanging from a 1 kg box by its end. Once the tests have put NaN into the box they run only
// the substep's actions (ActionWorld::runActions, what stepSimulation calls after Bullet's own part
// of the substep), so that Bullet itself never computes with the NaN and the floating-point traps
// stay on for the ropes' code; NaNBodyInsideBulletNeverThrowsThroughTheStep below runs the whole step.
struct HangingFromBox {
  ActionWorld world{btVector3(0, 0, 0)};
  RopeWorld ropes{world.world()};
  btRigidBody* box = world.addBox(btVector3(0.05, 0.05, 0.05), 1.0, btVector3(0, 1.05, 0));
  RopeObject rope{Rod::fromSegment(limpRope(), Vec3(0, 1, 0), Vec3(1, 1, 0))};
  HangingFromBox() {
    ropes.addRope(rope);
    rope.attachToBody(rope.rod().beginParameter(), *box, btVector3(0, -0.05, 0));
  }
};

TEST(StepFailure, AttachedBodyWithNaNLinearVelocityIsSkippedNotThrown) {
  HangingFromBox scene;
  scene.world.step(2);
  ASSERT_TRUE(scene.rope.lastStep().ok);
  ASSERT_EQ(scene.rope.lastStep().skippedBodies, 0);
  scene.box->setLinearVelocity(btVector3(btScalar(kNaN), 0, 0));
  for (int i = 0; i < 3; ++i) {
    // The substep's actions only (see the comment above HangingFromBox).
    EXPECT_NO_THROW(scene.world.runActions(btScalar(kStep)));
    EXPECT_TRUE(scene.rope.lastStep().ok);  // the rope steps on without the body
    EXPECT_EQ(scene.rope.lastStep().skippedBodies, 2);  // as the attached body and as a contact candidate
  }
  EXPECT_EQ(scene.rope.warnings().skippedBodies, 6);
  EXPECT_TRUE(finiteRod(scene.rope.rod()));
}

TEST(StepFailure, AttachedBodyWithNaNAngularVelocityIsSkippedNotThrown) {
  HangingFromBox scene;
  scene.world.step(2);
  scene.box->setAngularVelocity(btVector3(0, 0, btScalar(kInf)));
  EXPECT_NO_THROW(scene.world.runActions(btScalar(kStep)));
  EXPECT_NO_THROW(scene.world.runActions(btScalar(kStep)));
  EXPECT_TRUE(scene.rope.lastStep().ok);
  EXPECT_EQ(scene.rope.lastStep().skippedBodies, 2);
  EXPECT_EQ(scene.rope.warnings().skippedBodies, 4);
  EXPECT_TRUE(finiteRod(scene.rope.rod()));
}

// The case as a user meets it: a body Bullet itself integrates with a NaN velocity (so the
// traps are off for Bullet's sake). Nothing escapes any step and the rope stays finite.
TEST(StepFailure, NaNBodyInsideBulletNeverThrowsThroughTheStep) {
  test::ScopedNoFloatingPointTraps bulletComputesWithNaN;
  ActionWorld world;
  RopeWorld ropes(world.world());
  btRigidBody* box = world.addBox(btVector3(0.05, 0.05, 0.05), 1.0, btVector3(0, 1.05, 0));
  RopeObject rope(Rod::fromSegment(limpRope(), Vec3(0, 1, 0), Vec3(1, 1, 0)));
  ropes.addRope(rope);
  rope.attachToBody(0.0, *box, btVector3(0, -0.05, 0));
  world.step(5);
  box->setLinearVelocity(btVector3(btScalar(kNaN), 0, 0));
  for (int i = 0; i < 20; ++i) ASSERT_NO_THROW(world.step(1));
  EXPECT_TRUE(finiteRod(rope.rod()));
  EXPECT_GE(rope.warnings().skippedBodies, 20);
}

// Bullet hands its actions whatever time step the user gave stepSimulation when maxSubSteps is 0.
TEST(StepFailure, BadTimeStepIsSkippedAndReported) {
  ActionWorld world;
  RopeWorld ropes(world.world());
  RopeObject rope(Rod::fromSegment(limpRope(), Vec3(0, 1, 0), Vec3(1, 1, 0)));
  ropes.addRope(rope);
  world.step(3);
  const std::vector<double> before = rodState(rope.rod());
  int skipped = 0;
  for (const double h : {-1.0 / 60.0, kNaN, kInf, -kInf, 0.0, -0.0}) {
    EXPECT_NO_THROW(world.runActions(btScalar(h))) << h;
    ++skipped;
    EXPECT_EQ(ropes.warnings().skippedSubsteps, skipped) << h;
    EXPECT_STRNE(ropes.lastReport().failure, "") << h;
    ASSERT_EQ(ropes.lastReport().ropes.size(), 1u);
    EXPECT_FALSE(rope.lastStep().ok) << h;
    EXPECT_STRNE(rope.lastStep().failure, "") << h;
    EXPECT_TRUE(sameBits(rodState(rope.rod()), before)) << h;
  }
  EXPECT_EQ(rope.warnings().failedSteps, skipped);
  EXPECT_EQ(rope.warnings().consecutiveFailures, skipped);
  // The next good substep runs as if nothing had happened.
  world.runActions(btScalar(kStep));
  EXPECT_TRUE(rope.lastStep().ok);
  EXPECT_STREQ(ropes.lastReport().failure, "");
  EXPECT_EQ(rope.warnings().consecutiveFailures, 0);
  EXPECT_FALSE(sameBits(rodState(rope.rod()), before));  // it fell
}

// The same through stepSimulation itself, as the issue reported it (traps off: Bullet computes with
// the NaN time step too).
TEST(StepFailure, StepSimulationWithBadTimeStepDoesNotThrow) {
  test::ScopedNoFloatingPointTraps bulletComputesWithNaN;
  ActionWorld world;
  RopeWorld ropes(world.world());
  RopeObject rope(Rod::fromSegment(limpRope(), Vec3(0, 1, 0), Vec3(1, 1, 0)));
  KinematicRope hose(TractrixRope(PointList{Vec3(0, 2, 0), Vec3(1, 2, 0)}, TractrixSettings{}));
  ropes.addRope(rope);
  hose.addToWorld(world.world());
  const std::vector<double> before = rodState(rope.rod());
  for (const double h : {-1.0 / 60.0, kNaN, kInf}) {
    EXPECT_NO_THROW(world.world().stepSimulation(btScalar(h), 0)) << h;
  }
  EXPECT_EQ(ropes.warnings().skippedSubsteps, 3);
  EXPECT_EQ(hose.warnings().skippedSubsteps, 3);
  EXPECT_TRUE(sameBits(rodState(rope.rod()), before));
  hose.removeFromWorld();
}

TEST(StepFailure, SubstepCallbackExceptionIsCaughtAndCounted) {
  ActionWorld world;
  RopeWorld ropes(world.world());
  RopeObject rope(Rod::fromSegment(limpRope(), Vec3(0, 1, 0), Vec3(1, 1, 0)));
  ropes.addRope(rope);
  int calls = 0;
  ropes.setSubstepCallback([&](const ContactReport&) {
    ++calls;
    throw std::runtime_error("user callback failed");
  });
  EXPECT_NO_THROW(world.step(3));
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(ropes.warnings().callbackExceptions, 3);
  EXPECT_EQ(ropes.lastError(), "user callback failed");
  EXPECT_TRUE(rope.lastStep().ok);  // the ropes stepped normally before the callback ran
  ropes.setSubstepCallback([](const ContactReport&) { throw 42; });  // not even a std::exception
  EXPECT_NO_THROW(world.step(1));
  EXPECT_EQ(ropes.warnings().callbackExceptions, 4);
}

// A user's concave shape that throws from processAllTriangles: the exception leaves the rope's
// narrowphase in the middle of its substep. That rope keeps its state and reports why; another rope
// in the same world steps on; once the shape behaves again so does the rope.
TEST(StepFailure, NarrowphaseExceptionFailsOnlyThatRopesSubstep) {
  ActionWorld world;
  RopeWorld ropes(world.world());
  test::ThrowingGroundShape groundShape(2);
  world.addStatic(groundShape, btVector3(0, 0, 0));
  RopeObject touching(Rod::fromSegment(limpRope(), Vec3(-0.5, 0.012, 0), Vec3(0.5, 0.012, 0)));
  RopeObject falling(Rod::fromSegment(limpRope(), Vec3(-0.5, 1.5, 0), Vec3(0.5, 1.5, 0)));
  ropes.addRope(touching);
  ropes.addRope(falling);
  world.step(2);
  ASSERT_TRUE(touching.lastStep().ok);
  ASSERT_FALSE(touching.contacts().empty());  // the ground is found by the rope's narrowphase

  groundShape.arm(true);
  const std::vector<double> touchingBefore = rodState(touching.rod());
  const std::vector<double> fallingBefore = rodState(falling.rod());
  EXPECT_NO_THROW(world.step(3));
  EXPECT_FALSE(touching.lastStep().ok);
  EXPECT_NE(std::string(touching.lastStep().failure).find("exception"), std::string::npos);
  EXPECT_EQ(touching.lastError(), "injected narrowphase failure");
  EXPECT_EQ(touching.warnings().exceptions, 3);
  EXPECT_EQ(touching.warnings().failedSteps, 3);
  EXPECT_EQ(touching.warnings().consecutiveFailures, 3);
  EXPECT_EQ(touching.lastStep().contacts, 0);
  EXPECT_TRUE(sameBits(rodState(touching.rod()), touchingBefore));
  EXPECT_TRUE(falling.lastStep().ok);
  EXPECT_FALSE(sameBits(rodState(falling.rod()), fallingBefore));
  EXPECT_EQ(falling.warnings().total(), 0);

  groundShape.arm(false);
  world.step(1);
  EXPECT_TRUE(touching.lastStep().ok);
  EXPECT_EQ(touching.warnings().consecutiveFailures, 0);
  EXPECT_EQ(touching.warnings().failedSteps, 3);
}

TEST(StepFailure, KinematicRopePathExceptionMakesItHold) {
  ActionWorld world;
  KinematicRope hose(TractrixRope(PointList{Vec3(0, 1, 0), Vec3(1, 1, 0)}, TractrixSettings{}));
  hose.addToWorld(world.world());
  hose.followPath([](double t) { return btVector3(btScalar(-0.1 * t), 1, 0); });
  world.step(5);
  ASSERT_EQ(hose.lastStep().targetFailure, nullptr);
  const btVector3 held = hose.leadingEnd();
  hose.followPath([](double t) -> btVector3 {
    if (t > 0.0) throw std::runtime_error("path failed");
    return btVector3(0, 0, 0);
  });
  EXPECT_NO_THROW(world.step(4));
  EXPECT_NE(hose.lastStep().targetFailure, nullptr);
  EXPECT_EQ(hose.leadingEnd(), held);
  EXPECT_EQ(hose.warnings().pathExceptions, 4);
  EXPECT_EQ(hose.warnings().targetFailures, 4);
  EXPECT_EQ(hose.lastError(), "path failed");
  hose.followPath([](double) -> btVector3 { throw 7; });
  EXPECT_NO_THROW(world.step(1));
  EXPECT_EQ(hose.warnings().pathExceptions, 5);
  hose.setTarget(btVector3(btScalar(0.2), 1, 0));
  world.step(1);
  EXPECT_EQ(hose.lastStep().targetFailure, nullptr);
  EXPECT_EQ(hose.leadingEnd(), btVector3(btScalar(0.2), 1, 0));
}

TEST(StepFailure, KinematicRopeBadTimeStepIsSkipped) {
  ActionWorld world;
  KinematicRope hose(TractrixRope(PointList{Vec3(0, 1, 0), Vec3(1, 1, 0)}, TractrixSettings{}));
  hose.addToWorld(world.world());
  hose.setTarget(btVector3(btScalar(-0.1), 1, 0));
  world.runActions(btScalar(kStep));
  const double time = hose.lastStep().time;
  hose.setTarget(btVector3(btScalar(-0.2), 1, 0));
  for (const double h : {kNaN, -kStep, kInf, 0.0}) {
    EXPECT_NO_THROW(world.runActions(btScalar(h))) << h;
    EXPECT_NE(hose.lastStep().failure, nullptr) << h;
    EXPECT_EQ(hose.lastStep().time, time) << h;  // the clock did not move
    EXPECT_EQ(hose.leadingEnd(), btVector3(btScalar(-0.1), 1, 0)) << h;
  }
  EXPECT_EQ(hose.warnings().skippedSubsteps, 4);
  world.runActions(btScalar(kStep));
  EXPECT_EQ(hose.lastStep().failure, nullptr);
  EXPECT_EQ(hose.leadingEnd(), btVector3(btScalar(-0.2), 1, 0));
}

// An exception from the narrowphase of a kinematic rope (a dynamic body with a user's concave shape
// that throws) leaves the rope's substep through its action's guard: counted, reported, no throw.
TEST(StepFailure, KinematicRopeNarrowphaseExceptionIsCaught) {
  ActionWorld world(btVector3(0, 0, 0));
  test::ThrowingGroundShape shape(1);
  btRigidBody::btRigidBodyConstructionInfo info(1.0, nullptr, &shape, btVector3(1, 1, 1));
  info.m_startWorldTransform.setOrigin(btVector3(0.5, btScalar(0.995), 0));
  btRigidBody plate(info);
  world.world().addRigidBody(&plate);
  KinematicRope hose(TractrixRope(PointList{Vec3(0, 1, 0), Vec3(1, 1, 0)}, TractrixSettings{}));
  hose.addToWorld(world.world());
  shape.arm(true);
  EXPECT_NO_THROW(world.runActions(btScalar(kStep)));
  EXPECT_NE(hose.lastStep().failure, nullptr);
  EXPECT_EQ(hose.warnings().exceptions, 1);
  EXPECT_EQ(hose.lastError(), "injected narrowphase failure");
  shape.arm(false);
  world.runActions(btScalar(kStep));
  EXPECT_EQ(hose.lastStep().failure, nullptr);
  EXPECT_EQ(hose.warnings().exceptions, 1);
  hose.removeFromWorld();
  world.world().removeRigidBody(&plate);
}

// A body with a NaN velocity in a kinematic rope's way gets no (NaN) impulse; it is counted.
TEST(StepFailure, KinematicRopePassesThroughNaNBody) {
  ActionWorld world(btVector3(0, 0, 0));
  btRigidBody* box = world.addBox(btVector3(0.1, 0.1, 0.1), 1.0, btVector3(0.5, 1, 0));
  KinematicRope hose(TractrixRope(PointList{Vec3(0, 1, 0), Vec3(1, 1, 0)}, TractrixSettings{}));
  hose.addToWorld(world.world());
  world.step(1);
  box->setLinearVelocity(btVector3(0, btScalar(kNaN), 0));
  EXPECT_NO_THROW(world.runActions(btScalar(kStep)));  // only the rope reads the NaN
  EXPECT_NO_THROW(world.runActions(btScalar(kStep)));
  EXPECT_EQ(hose.lastStep().unsupportedBodies, 1);
  EXPECT_EQ(hose.warnings().unsupportedBodies, 2);
  EXPECT_TRUE(hose.lastStep().contacts.empty());
  EXPECT_TRUE(std::isfinite(box->getAngularVelocity().length()));
  hose.removeFromWorld();
}

TEST(StepFailure, OneSecondStepOfAHangingRopeIsDetectedAsGarbage) {
  // Released horizontal, hanging from its pinned end: in one linearised step of 1 s the rope swings
  // along its tangents, which stretches it (3.75 times its rest length before the check).
  Rod rod = Rod::fromSegment(RodSettings{}, Vec3(0, 0, 0), Vec3(1, 0, 0));
  rod.pin(rod.beginParameter());
  const std::vector<double> before = rodState(rod);
  StepReport report;
  {
    test::ScopedNoFloatingPointTraps hugeStepOnPurpose;
    report = rod.step(1.0);
  }
  EXPECT_FALSE(report.ok);
  EXPECT_NE(std::string(report.failure).find("kMaxStepStretch"), std::string::npos) << report.failure;
  EXPECT_TRUE(sameBits(rodState(rod), before));
  // The same rope at an ordinary step is fine.
  EXPECT_TRUE(rod.step(kStep).ok);
}

TEST(StepFailure, RopeThatKeepsFailingIsPutToRestAndStillCollides) {
  ActionWorld world;
  world.addBox(btVector3(2, 0.05, 2), 0.0, btVector3(0, -0.05, 0));  // ground, top at y = 0
  const double r = RodSettings{}.radius;
  RopeObject rope(Rod::fromSegment(RodSettings{}, Vec3(-0.5, r, 0), Vec3(0.5, r, 0)));
  RopeWorld ropes(world.world());
  ropes.addRope(rope);
  // An impossible constraint: the end pinned to a target 100 m away. Every step would stretch the
  // first control-polygon leg a hundredfold and fails (Rod::kMaxStepStretch); the rope keeps its state.
  const int pin = rope.attachToPoint(rope.rod().beginParameter(), btVector3(-0.5, btScalar(r), 0));
  rope.setAttachmentTarget(pin, btVector3(-100, btScalar(r), 0));
  world.step(RopeObject::kFailuresBeforeRest - 1);
  EXPECT_FALSE(rope.resting());
  EXPECT_EQ(rope.warnings().consecutiveFailures, RopeObject::kFailuresBeforeRest - 1);
  world.step(1);
  ASSERT_TRUE(rope.resting());
  EXPECT_TRUE(rope.lastStep().resting);
  EXPECT_STREQ(rope.lastStep().failure, RopeObject::kRestingFailure);
  EXPECT_EQ(rope.warnings().timesPutToRest, 1);
  EXPECT_EQ(rope.warnings().failedSteps, RopeObject::kFailuresBeforeRest);
  for (const Vec3& v : rope.rod().velocities()) EXPECT_EQ(v.norm(), 0.0);

  // Frozen, still colliding: a 1 kg box dropped across the rope's middle comes to rest on it (on the
  // ground it would sit 2 r lower), and the rope does not move.
  const std::vector<double> frozen = rodState(rope.rod());
  btRigidBody* box = world.addBox(btVector3(0.05, 0.05, 0.05), 1.0, btVector3(0, btScalar(0.15), 0));
  world.step(480);
  const double bottom = static_cast<double>(box->getCenterOfMassPosition().y()) - 0.05;
  EXPECT_GT(bottom, 2 * r - 1e-3) << "the box fell through the resting rope";
  EXPECT_LT(std::abs(static_cast<double>(box->getLinearVelocity().y())), 0.05);
  EXPECT_GT(rope.lastStep().contacts, 0);
  EXPECT_TRUE(sameBits(rodState(rope.rod()), frozen));
  EXPECT_EQ(rope.warnings().restingSubsteps, 480);
  EXPECT_EQ(rope.warnings().failedSteps, RopeObject::kFailuresBeforeRest);  // resting substeps are not failures
  std::printf("resting rope under a 1 kg box: box bottom %.4g m above the ground (rope top %.4g m), %d contacts\n",
              bottom, 2 * r, rope.lastStep().contacts);

  // Woken with the impossible pin gone, it steps again (and the box on it moves it).
  rope.removeAttachment(pin);
  rope.wake();
  world.step(1);
  EXPECT_FALSE(rope.resting());
  EXPECT_TRUE(rope.lastStep().ok) << rope.lastStep().failure;
  EXPECT_FALSE(rope.lastStep().resting);
}

}  // namespace
}  // namespace rope::bullet
