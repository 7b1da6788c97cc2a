// SPDX-License-Identifier: MIT
// Winches on ropes in a Bullet world (bullet_bridge/winch.h; docs/method.md §16): a winch on a body,
// a winch that stalls at an attachment, winchTo stopping exactly, and a cut handing the end's winch on.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "bullet_bridge/rope_world.h"
#include "demos/scenes/physics_world.h"

namespace rope::bullet {
namespace {

constexpr double kStep = 1.0 / 240.0;

void stepWorld(btDiscreteDynamicsWorld& world, int steps) {
  for (int i = 0; i < steps; ++i) world.stepSimulation(btScalar(kStep), 1, btScalar(kStep));
}

RodSettings winchRope() {
  RodSettings rod;
  rod.stiffnessDamping = 0.01;  // the box's bounce on the rope decays
  return rod;
}

TEST(Winch, OnABodyLowersTheLoadByThePaidOutLength) {
  // The winch sits on a static trolley (a body attachment at the rope's begin): it moves with the
  // end, so the 1 kg box goes down by the paid-out length (times 1 + strain).
  demos::PhysicsWorld physics;
  btRigidBody* trolley = physics.addBox(btVector3(0.05, 0.05, 0.05), 0.0, btVector3(0, 2.0, 0));
  btRigidBody* box = physics.addBox(btVector3(0.05, 0.05, 0.05), 1.0, btVector3(0, 0.9, 0));
  box->setActivationState(DISABLE_DEACTIVATION);
  RopeObject rope(Rod::fromSegment(winchRope(), Vec3(0, 1.95, 0), Vec3(0, 0.95, 0)));
  physics.ropes().addRope(rope);
  const int top = rope.attachToBody(0.0, *trolley, btVector3(0, -0.05, 0));
  rope.attachToBody(1.0, *box, btVector3(0, 0.05, 0));
  stepWorld(physics.world(), 480);
  const double y0 = static_cast<double>(box->getCenterOfMassPosition().y());
  rope.setWinchSpeed(RopeEnd::kBegin, 0.2);
  stepWorld(physics.world(), 240);
  rope.setWinchSpeed(RopeEnd::kBegin, 0.0);
  stepWorld(physics.world(), 480);
  ASSERT_TRUE(rope.lastStep().ok);
  EXPECT_NEAR(rope.winch(RopeEnd::kBegin).paidOut, 0.2, 1e-12);
  EXPECT_NEAR(rope.rod().restLength(), 1.2, 1e-12);
  EXPECT_EQ(rope.attachments()[0].id, top);
  EXPECT_EQ(rope.attachments()[0].s, rope.rod().beginParameter());
  const double strain = 9.81 / rope.rod().settings().axialStiffness();
  EXPECT_NEAR(y0 - static_cast<double>(box->getCenterOfMassPosition().y()), 0.2 * (1.0 + strain), 2e-4);
  EXPECT_NEAR(rope.winchTension(RopeEnd::kBegin), (1.0 + rope.rod().mass()) * 9.81, 0.01 * 9.81);
}

TEST(Winch, ReelingInStallsAtAnAttachment) {
  demos::PhysicsWorld physics;
  btRigidBody* box = physics.addBox(btVector3(0.05, 0.05, 0.05), 1.0, btVector3(0, 1.0, 0));
  box->setActivationState(DISABLE_DEACTIVATION);
  RopeObject rope(Rod::fromSegment(winchRope(), Vec3(0, 2, 0), Vec3(0, 1, 0)));
  physics.ropes().addRope(rope);
  rope.attachToPoint(0.0, btVector3(0, 2, 0));
  rope.attachToBody(0.5, *box, btVector3(0, 0, 0));
  const double limit = rope.reelInLimit(RopeEnd::kBegin);
  EXPECT_NEAR(limit, 0.5 - rope.rod().settings().minKnotSpacing, 1e-12);
  rope.setWinchSpeed(RopeEnd::kBegin, -0.5);
  stepWorld(physics.world(), 300);  // 1.25 s: the limit is reached after 0.99 s
  ASSERT_TRUE(rope.lastStep().ok);
  EXPECT_TRUE(rope.winch(RopeEnd::kBegin).stalled);
  EXPECT_EQ(rope.winch(RopeEnd::kBegin).speed, 0.0);
  EXPECT_NEAR(rope.rod().restLength(), 1.0 - limit, 1e-12);
  EXPECT_NEAR(rope.winch(RopeEnd::kBegin).paidOut, -limit, 1e-12);
  EXPECT_EQ(rope.attachments()[1].s, 0.5);  // the attachment kept its material point
  EXPECT_EQ(rope.reelInLimit(RopeEnd::kBegin), 0.0);
}

TEST(Winch, WinchToStopsExactlyAtItsLengthAndACutHandsTheEndsWinchOn) {
  demos::PhysicsWorld physics;
  RopeObject rope(Rod::fromSegment(winchRope(), Vec3(0, 2, 0), Vec3(1, 2, 0)));
  physics.ropes().addRope(rope);
  rope.attachToPoint(0.0, btVector3(0, 2, 0));
  rope.winchTo(RopeEnd::kEnd, 1.234, 0.3);
  stepWorld(physics.world(), 240);
  ASSERT_TRUE(rope.lastStep().ok);
  EXPECT_NEAR(rope.rod().restLength(), 1.234, 1e-12);
  EXPECT_EQ(rope.winch(RopeEnd::kEnd).speed, 0.0);
  EXPECT_FALSE(rope.winch(RopeEnd::kEnd).stalled);
  rope.winchTo(RopeEnd::kEnd, 0.9, 0.3);
  EXPECT_LT(rope.winch(RopeEnd::kEnd).speed, 0.0);
  std::unique_ptr<RopeObject> piece = rope.cut(0.5);
  EXPECT_EQ(rope.winch(RopeEnd::kEnd).speed, 0.0);
  EXPECT_NEAR(piece->winch(RopeEnd::kEnd).speed, -0.3, 0.0);
  EXPECT_NEAR(piece->winch(RopeEnd::kEnd).targetLength, 0.4, 1e-12);  // its share of the 0.9 m
  stepWorld(physics.world(), 300);  // 0.334 m at 0.3 m/s
  EXPECT_NEAR(piece->rod().restLength() + rope.rod().restLength(), 0.9, 1e-12);
  EXPECT_NEAR(rope.rod().restLength(), 0.5, 1e-12);
  physics.ropes().removeRope(*piece);
}

}  // namespace
}  // namespace rope::bullet
