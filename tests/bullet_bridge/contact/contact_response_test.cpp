// SPDX-License-Identifier: MIT
// Contact response (bullet_bridge/contact/contact_response.h): the linearised penalty/friction law against
// its formulas, and the friction ramp scenario (stays for mu > tan(angle), slides at
// g (sin - mu cos) for mu < tan(angle)).
#include "bullet_bridge/contact/contact_response.h"

#include <gtest/gtest.h>

#include <cmath>

#include "bullet_bridge/rope_world.h"
#include "demos/scenes/drape_scene.h"
#include "demos/scenes/physics_world.h"

namespace rope::bullet {
namespace {

ContactLaw law() {
  ContactLaw law;
  law.stiffness = 1e4;
  law.damping = 20.0;
  law.friction = 0.5;
  law.frictionVelocity = 1e-3;
  return law;
}

TEST(ContactResponse, RestingContactPushesAlongNormal) {
  const Vec3 n(0, 1, 0);
  const ContactSpring spring = contactSpring(law(), -0.002, n, Vec3::Zero(), Vec3::Zero(), 0.01);
  EXPECT_NEAR(spring.force.y(), 20.0, 1e-12);  // -k d
  EXPECT_NEAR(spring.force.x(), 0.0, 1e-12);
  EXPECT_NEAR(spring.stiffness(1, 1), 1e4, 1e-9);
  EXPECT_NEAR(spring.stiffness(0, 0), 0.0, 1e-12);  // no tangential stiffness
  // Sticking: the viscous friction coefficient is mu f_n / v_reg in the tangent plane.
  EXPECT_NEAR(spring.damping(0, 0), 0.5 * 20.0 / 1e-3, 1e-6);
  EXPECT_NEAR(spring.damping(1, 1), 20.0, 1e-12);
}

// A contact still apart but closing within the step is a damper towards the approach speed -d/h
// that lands the rope on the surface: no spring (it would pull before contact), no friction yet.
TEST(ContactResponse, SpeculativeContactLandsTheRopeOnTheSurface) {
  ContactLaw speculative = law();
  speculative.speculativeDamping = 1e3;
  const Vec3 n(0, 1, 0);
  const double gap = 0.01, h = 1.0 / 240.0;
  const Vec3 u(0.3, -20.0, 0.0);
  const ContactSpring spring = contactSpring(speculative, gap, n, u, Vec3::Zero(), h);
  EXPECT_NEAR(spring.force.y(), 1e3 * (-gap / h + 20.0), 1e-9);
  EXPECT_EQ(spring.stiffness, Eigen::Matrix3d::Zero());
  EXPECT_NEAR(spring.damping(1, 1), 1e3, 1e-12);
  EXPECT_NEAR(spring.damping(0, 0), 0.0, 1e-12);
  EXPECT_NEAR(spring.force.x(), 0.0, 1e-12);
  // A 2 g point of rope under this law alone, stepped implicitly: (m + h c) du = h f0.
  const double mass = 0.002;
  const double du = h * spring.force.y() / (mass + h * spring.damping(1, 1));
  const double endGap = gap + h * (u.y() + du);
  EXPECT_GT(endGap, -1e-4);  // on the surface to within a tenth of a millimetre
  EXPECT_LT(endGap, 1e-4);
}

TEST(ContactResponse, SlidingFrictionIsCoulomb) {
  const Vec3 n(0, 1, 0);
  const Vec3 u(2.0, 0, 0);  // sliding at 2 m/s >> v_reg
  const ContactSpring spring = contactSpring(law(), -0.002, n, u, Vec3::Zero(), 0.01);
  // Explicit part at the current slip: mu f_n against the slip.
  EXPECT_NEAR(spring.force.x(), -0.5 * 20.0, 1e-9);
  // At the same slip after the step the force is the same (steady sliding).
  const Vec3 uNew(2.0, 0.0, 0.0);
  const Vec3 force = endOfStepForce(spring, u, uNew, 0.01);
  EXPECT_NEAR(force.x(), -10.0, 1e-9);
  EXPECT_NEAR(force.y(), 20.0 - 0.01 * 1e4 * 0.0, 1e-9);
}

TEST(ContactResponse, BodyVelocityEntersRelativeToTheRope) {
  const Vec3 n(0, 1, 0);
  const Vec3 v(1.0, 0.5, 0.0);  // body moving up into the rope and sideways
  const ContactSpring spring = contactSpring(law(), -0.001, n, v, v, 0.01);
  // Rope moving with the body: no damping or friction; the body's approach over the step is anticipated.
  EXPECT_NEAR(spring.force.x(), 0.0, 1e-12);
  EXPECT_NEAR(spring.force.y(), 10.0 + 1e4 * 0.01 * 0.5, 1e-9);
  // End of step with the rope still moving with the body: -k (d + h n.(u_new - v_b)) = -k d.
  EXPECT_NEAR(endOfStepForce(spring, v, v, 0.01).y(), 10.0, 1e-9);
}

TEST(ContactResponse, ActivationPredictsClosingGaps) {
  const Vec3 n(0, 1, 0);
  EXPECT_TRUE(contactActive(-1e-4, n, Vec3::Zero(), Vec3::Zero(), 0.01));
  EXPECT_FALSE(contactActive(0.005, n, Vec3::Zero(), Vec3::Zero(), 0.01));
  EXPECT_TRUE(contactActive(0.005, n, Vec3(0, -1, 0), Vec3::Zero(), 0.01));     // closes 1 cm per step
  EXPECT_FALSE(contactActive(0.005, n, Vec3(0, -1, 0), Vec3(0, -1, 0), 0.01));  // body moves away as fast
  EXPECT_TRUE(contactActive(-0.001, n, Vec3(0, 0.5, 0), Vec3::Zero(), 0.01));   // penetrating
}

TEST(ContactResponse, CapForBodyLimitsToExplicitStability) {
  double k = 1e6, c = 1e3;
  capForBody(1.0, 0.01, 0.25, k, c);  // 1 kg body
  EXPECT_DOUBLE_EQ(k, 0.25 / 1e-4);
  EXPECT_DOUBLE_EQ(c, 0.25 / 0.01);
  double k2 = 1e6, c2 = 1e3;
  capForBody(0.0, 0.01, 0.25, k2, c2);  // static body: unchanged
  EXPECT_DOUBLE_EQ(k2, 1e6);
  EXPECT_DOUBLE_EQ(c2, 1e3);
}

// A 0.5 m rope laid down the slope of a static 30 degree ramp, run for 2 s.
struct RampResult {
  double travel = 0.0;         // m along the slope, downhill positive, over the last second
  double acceleration = 0.0;   // m/s^2 along the slope over the last second
  double stickingShare = 0.0;  // of the active contacts in the last substep
};

RampResult runRamp(double mu) {
  const double angle = 30.0 * 3.14159265358979323846 / 180.0;
  demos::PhysicsWorld physics;
  btTransform ramp;
  ramp.setIdentity();
  ramp.setRotation(btQuaternion(btVector3(0, 0, 1), btScalar(-angle)));  // descends towards +x
  // Friction 1 on the ramp: the contact's coefficient (the product, friction_combination.h) is mu.
  physics.addBox(btVector3(3.0, 0.1, 0.5), 0.0, ramp)->setFriction(btScalar(1.0));
  const Vec3 down(std::cos(angle), -std::sin(angle), 0.0);
  const Vec3 up(std::sin(angle), std::cos(angle), 0.0);  // the ramp's top-face normal
  RodSettings rod = demos::DrapeSceneSettings::defaultRod();
  rod.restLength = 0.5;
  rod.massDamping = 0.0;  // no air drag: only friction holds the rope back
  const Vec3 start = -0.5 * down + (0.1 + rod.radius + 1e-4) * up;
  BulletRopeSettings bridge;
  bridge.friction = mu;
  RopeObject rope(Rod::fromSegment(rod, start, start + 0.5 * down), bridge);
  physics.ropes().addRope(rope);
  const double h = 1.0 / 240.0;
  for (int i = 0; i < 240; ++i) physics.world().stepSimulation(btScalar(h), 1, btScalar(h));
  const double s = 0.5 * (rope.rod().beginParameter() + rope.rod().endParameter());
  const Vec3 before = rope.rod().position(s);
  const double speedBefore = rope.rod().velocity(s).dot(down);
  for (int i = 0; i < 240; ++i) {
    physics.world().stepSimulation(btScalar(h), 1, btScalar(h));
  }
  RampResult result;
  result.travel = (rope.rod().position(s) - before).dot(down);
  result.acceleration = rope.rod().velocity(s).dot(down) - speedBefore;  // over 1 s
  int active = 0, sticking = 0;
  for (const RopeContactRecord& contact : rope.contacts()) {
    if (!contact.active) continue;
    ++active;
    sticking += contact.sticking ? 1 : 0;
  }
  result.stickingShare = active > 0 ? static_cast<double>(sticking) / active : 0.0;
  return result;
}

TEST(ContactResponseScenario, RopeOnRampStaysWhenFrictionExceedsSlope) {
  const RampResult result = runRamp(0.7);  // tan(30 deg) = 0.577
  // The regularised law creeps at about v_reg tan / mu (0.8 mm/s): "stays" means within a few mm.
  EXPECT_LT(std::abs(result.travel), 0.003);
  EXPECT_GT(result.stickingShare, 0.99);
  std::printf("ramp mu=0.7: travel %.3g m in 1 s, sticking share %.2f\n", result.travel, result.stickingShare);
}

TEST(ContactResponseScenario, RopeOnRampSlidesWhenFrictionIsBelowSlope) {
  const double mu = 0.4;
  const double angle = 30.0 * 3.14159265358979323846 / 180.0;
  const double a = 9.81 * (std::sin(angle) - mu * std::cos(angle));
  const RampResult result = runRamp(mu);
  // Sliding, with the Coulomb acceleration. The discrete friction bound (mu times the positive
  // contact forces at the start of the substep) runs a few percent above mu N, hence 10%.
  EXPECT_GT(result.travel, 0.5);
  EXPECT_NEAR(result.acceleration, a, 0.1 * a);
  EXPECT_LT(result.stickingShare, 0.01);
  std::printf("ramp mu=0.4: travel %.3f m in the 2nd second, acceleration %.4f m/s^2 vs g(sin - mu cos) %.4f\n",
              result.travel, result.acceleration, a);
}

}  // namespace
}  // namespace rope::bullet
