// SPDX-License-Identifier: MIT
// Scenario: a rope pendulum in a Bullet world — a 10 kg rigid ball on 1 m of thin rope (default
// RodSettings and BulletRopeSettings), hung from a fixed point and swung by 5 degrees. The rod's
// default BDF2 step (docs/method.md §8) must keep the swing as a Bullet rigid-body pendulum does; the
// attachment couples the two with backward Euler's weight, which the measured figures include.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "bullet_bridge/attachment.h"
#include "bullet_bridge/rope_world.h"
#include "demos/scenes/physics_world.h"

namespace rope::bullet {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kSwing = 5.0 * kPi / 180.0;
constexpr double kBall = 10.0;    // kg
constexpr double kRadius = 0.05;  // m, the ball's

btVector3 bt(const Vec3& v) { return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z())); }

struct Swing {
  double amplitudeKept = 0.0;  // largest |angle| in the last period over that in the first
  double period = 0.0;         // s, mean over the run
  double expectedPeriod = 0.0; // s
  double offset = 0.0;         // m, |ball's attachment point - rope's end| at the end of the run
};

Swing swingInBullet(double h, double seconds, double swingAngle = kSwing) {
  demos::PhysicsWorld physics;  // gravity -9.81 along y, no ground: nothing to touch
  RodSettings rod;
  rod.radius = 0.002;
  rod.linearDensity = 0.01;
  const Vec3 pivot(0, 3, 0);
  const Vec3 direction(std::sin(swingAngle), -std::cos(swingAngle), 0);
  const double length = 1.0;
  btRigidBody* ball = physics.addBody(std::make_unique<btSphereShape>(btScalar(kRadius)), kBall,
                                      btTransform(btQuaternion::getIdentity(),
                                                  bt(pivot + (length + kRadius) * direction)));
  ball->setActivationState(DISABLE_DEACTIVATION);
  RopeObject rope(Rod::fromSegment(rod, pivot, pivot + length * direction));
  physics.ropes().addRope(rope);
  rope.attachToPoint(0.0, bt(pivot));
  rope.attachToBody(rope.rod().endParameter(), *ball, btVector3(btScalar(-kRadius * direction.x()),
                                                                btScalar(-kRadius * direction.y()), 0));
  // The small-swing period of the rope and ball as one rigid body about the pivot: the ball's centre
  // at the arm L + r, its own inertia 2/5 M r^2 (it turns with the rope), the rope a uniform bar, and
  // the finite amplitude (1 + theta0^2/16).
  // The rope stretches under the ball's weight by the Green–Lagrange law T = (EA/2) g (g^2 - 1)
  // (method eq. 13; 0.78 % here, which alone lengthens the period by 0.39 %), and the ball hangs
  // T / k below the rope's end on the attachment's spring (k = AttachmentSettings::stiffness: 0.98 mm,
  // which alone lengthens the period by 0.049 %; AHangingBallStretchesTheAttachment... checks it).
  const double ea = rope.rod().settings().axialStiffness(), tension = kBall * 9.81;
  double gamma = 1.0 + tension / ea;
  for (int i = 0; i < 50; ++i) gamma -= (0.5 * ea * gamma * (gamma * gamma - 1.0) - tension) / (0.5 * ea * (3.0 * gamma * gamma - 1.0));
  const double arm = gamma * length + tension / AttachmentSettings{}.stiffness + kRadius;
  const double inertia = kBall * arm * arm + 0.4 * kBall * kRadius * kRadius + 0.01 * length * length / 3.0;
  const double torque = (kBall * arm + 0.01 * length * length / 2.0) * 9.81;
  Swing result;
  result.expectedPeriod = 2.0 * kPi * std::sqrt(inertia / torque) * (1.0 + swingAngle * swingAngle / 16.0);
  const auto angle = [&] {
    const btVector3 c = ball->getCenterOfMassPosition();
    return std::atan2(static_cast<double>(c.x()) - pivot.x(), pivot.y() - static_cast<double>(c.y()));
  };
  std::vector<double> crossings;
  double previous = angle(), first = 0.0, last = 0.0;
  const int steps = static_cast<int>(std::lround(seconds / h));
  for (int i = 1; i <= steps; ++i) {
    physics.world().stepSimulation(btScalar(h), 1, btScalar(h));
    EXPECT_TRUE(rope.lastStep().ok) << rope.lastStep().failure;
    const double now = angle();
    if (previous < 0.0 && now >= 0.0) crossings.push_back((i - 1 + previous / (previous - now)) * h);
    if (i * h <= result.expectedPeriod) first = std::max(first, std::abs(now));
    if (i * h >= seconds - result.expectedPeriod) last = std::max(last, std::abs(now));
    previous = now;
  }
  const btVector3 attachPoint =
      ball->getCenterOfMassTransform() * btVector3(btScalar(-kRadius * direction.x()), btScalar(-kRadius * direction.y()), 0);
  const Vec3 ropeEnd = rope.rod().position(rope.rod().endParameter());
  result.offset = std::sqrt(std::pow(double(attachPoint.x()) - ropeEnd.x(), 2) + std::pow(double(attachPoint.y()) - ropeEnd.y(), 2) +
                            std::pow(double(attachPoint.z()) - ropeEnd.z(), 2));
  if (crossings.size() >= 2) result.period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  if (first > 0.0) result.amplitudeKept = last / first;
  return result;
}

void report(double h, const Swing& swing) {
  std::printf("[bullet pendulum h=1/%.0f] keeps %.4f%% of the swing over 20 s, period %.6f s vs %.6f s (%.2e)\n",
              1.0 / h, 100.0 * swing.amplitudeKept, swing.period, swing.expectedPeriod,
              swing.period / swing.expectedPeriod - 1.0);
}

// A ball hanging at rest stretches the attachment's spring by exactly its weight over the stiffness,
// at any step: the rope predicts the ball point moving on under the ball's own forces (gravity) as
// well as under the rope's impulse. Measured after 20 s: 9.8100e-4 m at 1/240 s and at 1/60 s, for
// W / k = 9.81e-4 m (undamped, 9.794e-4 m at 1/240 s: what was left of the ball's bounce on the rope;
// before the ball's forces were predicted: 3.7 mm at 1/60 s).
TEST(BulletPendulum, AHangingBallStretchesTheAttachmentByItsWeightOverTheStiffness) {
  const double expected = kBall * 9.81 / AttachmentSettings{}.stiffness;
  for (const double h : {1.0 / 240, 1.0 / 60}) {
    const Swing still = swingInBullet(h, 20.0, 0.0);  // 20 s: the ball's bounce on the rope dies out
    std::printf("[bullet pendulum h=1/%.0f] hanging ball %.4e m below the rope's end (W / k = %.4e m)\n", 1.0 / h,
                still.offset, expected);
    EXPECT_NEAR(still.offset, expected, 2e-3 * expected) << "h = " << h;
  }
}

// Measured on the default damping: 99.933 % of the swing kept, period 0.012 % long (the rod alone,
// rod_time_integration_test: 99.991 % and 0.010 %). Backward Euler kept 69 %.
TEST(BulletPendulum, KeepsItsSwingAndPeriodOverTwentySecondsAt240Hz) {
  const double h = 1.0 / 240;
  const Swing swing = swingInBullet(h, 20.0);
  report(h, swing);
  // The targets were 98 % and 0.1 %; bounds a few times the measured loss and error.
  EXPECT_GE(swing.amplitudeKept, 0.997);
  EXPECT_LE(swing.amplitudeKept, 1.0 + 1e-3);
  EXPECT_LT(std::abs(swing.period / swing.expectedPeriod - 1.0), 3e-4);
}

// Measured: 99.60 % of the swing kept, period 0.086 % long (the rod alone: 99.59 % and 0.095 %, BDF2's
// own phase error at this step). Until the reference counted the attachment's stretch W / k in the
// arm, that 0.049 % looked like a coupling lag (0.129 %).
TEST(BulletPendulum, KeepsItsSwingAndPeriodOverTwentySecondsAt60Hz) {
  const double h = 1.0 / 60;
  const Swing swing = swingInBullet(h, 20.0);
  report(h, swing);
  // The targets: 95 % (a bound 2.5 times the measured loss instead) and 0.1 %.
  EXPECT_GE(swing.amplitudeKept, 0.99);
  EXPECT_LE(swing.amplitudeKept, 1.0 + 1e-3);
  EXPECT_LT(std::abs(swing.period / swing.expectedPeriod - 1.0), 1e-3);
}

}  // namespace
}  // namespace rope::bullet
