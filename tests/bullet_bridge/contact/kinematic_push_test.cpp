// SPDX-License-Identifier: MIT
// The one-way contact impulse of a kinematic rope on a body (contact/kinematic_push.h): after it the relative
// normal speed is exactly the target speed, it never pulls, friction stays within mu * j_n.
#include "bullet_bridge/contact/kinematic_push.h"

#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <memory>

namespace rope::bullet {
namespace {

constexpr double kH = 1.0 / 240.0;

struct Body {
  btBoxShape shape{btVector3(btScalar(0.2), btScalar(0.1), btScalar(0.05))};
  std::unique_ptr<btRigidBody> body;
  explicit Body(double mass) {
    btVector3 inertia(0, 0, 0);
    shape.calculateLocalInertia(static_cast<btScalar>(mass), inertia);
    btRigidBody::btRigidBodyConstructionInfo info(static_cast<btScalar>(mass), nullptr, &shape, inertia);
    info.m_startWorldTransform.setIdentity();
    info.m_startWorldTransform.setOrigin(btVector3(1, 2, 3));
    body = std::make_unique<btRigidBody>(info);
  }
};

// A contact on the body's +x face, off its centre (so the impulse also spins it), rope on the +x side.
Contact faceContact(double distance, bool offCentre = true) {
  Contact contact;
  contact.normal = btVector3(1, 0, 0);
  contact.pointOnBody = offCentre ? btVector3(btScalar(1.2), btScalar(2.07), btScalar(3.03)) : btVector3(btScalar(1.2), 2, 3);
  contact.distance = static_cast<btScalar>(distance);
  contact.pointOnCapsule = contact.pointOnBody + contact.normal * contact.distance;
  return contact;
}

double relativeNormalSpeed(const btRigidBody& body, const Contact& contact, const btVector3& ropeVelocity) {
  const btVector3 arm = contact.pointOnBody - body.getCenterOfMassPosition();
  return static_cast<double>(contact.normal.dot(ropeVelocity - body.getVelocityInLocalPoint(arm)));
}

// One contact through the solver; returns the impulse given to the body.
btVector3 applyOne(btRigidBody& body, const Contact& contact, const btVector3& ropeVelocity, const OneWayContactLaw& law) {
  OneWayContact c;
  c.contact = contact;
  c.ropeVelocity = ropeVelocity;
  solveOneWayContacts(body, &c, 1, kH, law);
  EXPECT_GE(c.normalImpulse, 0.0);
  EXPECT_LE(static_cast<double>(c.frictionImpulse.length()), law.friction * c.normalImpulse * (1 + 1e-12));
  return c.impulse();
}

TEST(KinematicPush, PenetratingContactLeavesAtTheRecoverySpeed) {
  for (double mass : {1e-3, 1.0, 1e4}) {
    Body b(mass);
    const Contact contact = faceContact(-0.004);
    const btVector3 ropeVelocity(-2.0, 0.3, 0.0);  // rope moving into the body at 2 m/s
    OneWayContactLaw law;
    law.friction = 0.0;
    const btVector3 impulse = applyOne(*b.body, contact, ropeVelocity, law);
    // v_n after = -recovery * d / h = 0.2 * 0.004 * 240 = 0.192 m/s (separating), whatever the mass.
    EXPECT_NEAR(relativeNormalSpeed(*b.body, contact, ropeVelocity), 0.2 * 0.004 / kH, 1e-12) << mass;
    EXPECT_LT(impulse.x(), 0.0);  // pushed along -n, away from the rope
    EXPECT_EQ(impulse.y(), 0.0);
    EXPECT_EQ(impulse.z(), 0.0);
    // Linear momentum gained is the impulse.
    EXPECT_NEAR(b.body->getLinearVelocity().x() * mass, impulse.x(), 1e-12 * (1.0 + std::fabs(impulse.x())));
    EXPECT_NE(b.body->getAngularVelocity().length(), 0.0);  // off-centre: it spins too
  }
}

TEST(KinematicPush, SeparatingAndSlowSpeculativeContactsGiveNothing) {
  Body b(2.0);
  OneWayContactLaw law;
  // Rope moving away from the body.
  EXPECT_EQ(applyOne(*b.body, faceContact(-0.001), btVector3(1, 0, 0), law), btVector3(0, 0, 0));
  // 5 mm apart, closing at 1 m/s: 4.2 mm per substep, the gap does not close.
  EXPECT_EQ(applyOne(*b.body, faceContact(0.005), btVector3(-1, 0, 0), law), btVector3(0, 0, 0));
  EXPECT_EQ(b.body->getLinearVelocity(), btVector3(0, 0, 0));
  EXPECT_EQ(b.body->getAngularVelocity(), btVector3(0, 0, 0));
  // Closing at 3 m/s would pass the gap: the body gets enough to close it exactly within h (to the
  // Gauss-Seidel tolerance: the friction of the turning body couples back into the normal).
  const Contact contact = faceContact(0.005);
  applyOne(*b.body, contact, btVector3(-3, 0, 0), law);
  EXPECT_NEAR(relativeNormalSpeed(*b.body, contact, btVector3(-3, 0, 0)), -0.005 / kH, 1e-5);
  law.friction = 0.0;  // without friction it is exact
  Body exact(2.0);
  applyOne(*exact.body, contact, btVector3(-3, 0, 0), law);
  EXPECT_NEAR(relativeNormalSpeed(*exact.body, contact, btVector3(-3, 0, 0)), -0.005 / kH, 1e-12);
}

TEST(KinematicPush, FrictionIsBoundedByTheNormalImpulse) {
  // Fast tangential slip along z at an off-centre point: sliding friction, exactly mu j_n, and the
  // normal condition still met after the friction turned the body.
  Body sliding(1.0);
  const Contact contact = faceContact(-0.002);
  const btVector3 ropeVelocity(-0.5, 0.0, 4.0);
  OneWayContactLaw law;
  law.friction = 0.4;
  OneWayContact c;
  c.contact = contact;
  c.ropeVelocity = ropeVelocity;
  solveOneWayContacts(*sliding.body, &c, 1, kH, law);
  EXPECT_NEAR(c.frictionImpulse.x(), 0.0, 1e-14);
  EXPECT_GT(c.frictionImpulse.z(), 0.0);  // dragged along with the rope
  EXPECT_NEAR(static_cast<double>(c.frictionImpulse.length()), 0.4 * c.normalImpulse, 1e-12);
  EXPECT_NEAR(relativeNormalSpeed(*sliding.body, contact, ropeVelocity), 0.2 * 0.002 / kH, 1e-6);
  // Slow slip at the face centre: friction sticks (the relative tangential velocity at the point goes
  // to zero), below the bound.
  Body sticking(1.0);
  const Contact centre = faceContact(-0.002, false);
  const btVector3 slow(-0.5, 0.0, 1e-3);
  const btVector3 impulse = applyOne(*sticking.body, centre, slow, law);
  const btVector3 arm = centre.pointOnBody - sticking.body->getCenterOfMassPosition();
  const btVector3 slip = slow - sticking.body->getVelocityInLocalPoint(arm);
  EXPECT_NEAR(slip.y(), 0.0, 1e-12);
  EXPECT_NEAR(slip.z(), 0.0, 1e-12);
  EXPECT_LT(std::hypot(impulse.y(), impulse.z()), 0.4 * -impulse.x());
}

TEST(KinematicPush, SeveralContactsShareTheLoadAndGravityIsAnticipated) {
  // A box resting on two contacts under its bottom face, symmetric about the centre, with gravity:
  // the solver splits the load evenly (no turning), and the velocity it leaves is +g h, which the
  // next substep's gravity cancels.
  Body b(2.0);
  b.body->setGravity(btVector3(0, btScalar(-9.81), 0));
  OneWayContact contacts[2];
  for (int i = 0; i < 2; ++i) {
    Contact& c = contacts[i].contact;
    c.normal = btVector3(0, -1, 0);
    c.pointOnBody = btVector3(btScalar(i == 0 ? 0.9 : 1.1), btScalar(1.9), 3);
    c.distance = 0;
    c.pointOnCapsule = c.pointOnBody;
  }
  OneWayContactLaw law;
  law.iterations = 30;
  solveOneWayContacts(*b.body, contacts, 2, kH, law);
  EXPECT_NEAR(b.body->getLinearVelocity().y(), 9.81 * kH, 1e-9);
  EXPECT_NEAR(b.body->getAngularVelocity().length(), 0.0, 1e-9);
  EXPECT_NEAR(contacts[0].normalImpulse, contacts[1].normalImpulse, 1e-9);
  EXPECT_NEAR(contacts[0].normalImpulse + contacts[1].normalImpulse, 2.0 * 9.81 * kH, 1e-9);
  // With a single sweep the first contact takes it all and the box turns.
  Body once(2.0);
  once.body->setGravity(btVector3(0, btScalar(-9.81), 0));
  law.iterations = 1;
  solveOneWayContacts(*once.body, contacts, 2, kH, law);
  EXPECT_GT(once.body->getAngularVelocity().length(), 1e-3);
}

}  // namespace
}  // namespace rope::bullet
