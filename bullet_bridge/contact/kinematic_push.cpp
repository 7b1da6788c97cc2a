// SPDX-License-Identifier: MIT
#include "bullet_bridge/contact/kinematic_push.h"

#include <cmath>

namespace rope::bullet {

void solveOneWayContacts(btRigidBody& body, OneWayContact* contacts, int count, double h, const OneWayContactLaw& law) {
  // The velocity the next substep will integrate: Bullet adds gravity before it moves the body.
  const btVector3 gravityKick = body.getGravity() * static_cast<btScalar>(h);
  for (int i = 0; i < count; ++i) {
    contacts[i].normalImpulse = 0.0;
    contacts[i].frictionImpulse.setZero();
  }
  bool touched = false;
  for (int sweep = 0; sweep < law.iterations; ++sweep) {
    for (int i = 0; i < count; ++i) {
      OneWayContact& c = contacts[i];
      const btVector3& n = c.contact.normal;
      const btVector3 arm = c.contact.pointOnBody - body.getCenterOfMassPosition();
      const double d = static_cast<double>(c.contact.distance);
      const double vMin = d >= 0.0 ? -d / h : -law.penetrationRecovery * d / h;

      // Normal: accumulated j_n >= 0.
      const double vn = static_cast<double>(n.dot(c.ropeVelocity - body.getVelocityInLocalPoint(arm) - gravityKick));
      const double normalDenominator = static_cast<double>(body.computeImpulseDenominator(c.contact.pointOnBody, n));
      const double updated = std::fmax(0.0, c.normalImpulse + (vMin - vn) / normalDenominator);
      const double deltaNormal = updated - c.normalImpulse;
      if (deltaNormal != 0.0) {
        body.applyImpulse(n * static_cast<btScalar>(-deltaNormal), arm);
        c.normalImpulse = updated;
        touched = true;
      }

      // Friction: the accumulated tangential impulse that would stop the slip, clamped to the cone
      // (to zero once the normal impulse is).
      if (law.friction > 0.0) {
        const btVector3 slip = c.ropeVelocity - body.getVelocityInLocalPoint(arm) - gravityKick;
        const btVector3 tangential = slip - n * n.dot(slip);
        const double speed = static_cast<double>(tangential.length());
        btVector3 target = c.frictionImpulse;
        if (speed > 0.0) {
          const btVector3 direction = tangential / static_cast<btScalar>(speed);
          const double tangentDenominator =
              static_cast<double>(body.computeImpulseDenominator(c.contact.pointOnBody, direction));
          target += direction * static_cast<btScalar>(speed / tangentDenominator);
        }
        const double bound = law.friction * c.normalImpulse;
        const double size = static_cast<double>(target.length());
        if (size > bound) target *= static_cast<btScalar>(bound / size);
        const btVector3 deltaFriction = target - c.frictionImpulse;
        if (!deltaFriction.isZero()) {
          body.applyImpulse(deltaFriction, arm);
          c.frictionImpulse = target;
          touched = true;
        }
      }
    }
  }
  if (touched) body.activate();
}

}  // namespace rope::bullet
