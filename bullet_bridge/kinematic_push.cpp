#include "bullet_bridge/kinematic_push.h"

#include <algorithm>
#include <cmath>

namespace rope::bullet {

btVector3 applyOneWayContact(btRigidBody& body, const Contact& contact, const btVector3& ropeVelocity, double h,
                             const OneWayContactLaw& law) {
  const btVector3& n = contact.normal;
  const btVector3 arm = contact.pointOnBody - body.getCenterOfMassPosition();
  const double d = static_cast<double>(contact.distance);
  const double vMin = d >= 0.0 ? -d / h : -law.penetrationRecovery * d / h;
  const double vn = static_cast<double>(n.dot(ropeVelocity - body.getVelocityInLocalPoint(arm)));
  if (!(vn < vMin)) return btVector3(0, 0, 0);

  const double normalDenominator = static_cast<double>(body.computeImpulseDenominator(contact.pointOnBody, n));
  const double jn = (vMin - vn) / normalDenominator;
  btVector3 total = n * static_cast<btScalar>(-jn);
  body.applyImpulse(total, arm);

  if (law.friction > 0.0) {
    // Tangential slip of the rope over the body after the normal impulse; the body is dragged along.
    const btVector3 slip = ropeVelocity - body.getVelocityInLocalPoint(arm);
    const btVector3 tangential = slip - n * n.dot(slip);
    const double speed = static_cast<double>(tangential.length());
    if (speed > 0.0) {
      const btVector3 direction = tangential / static_cast<btScalar>(speed);
      const double tangentDenominator =
          static_cast<double>(body.computeImpulseDenominator(contact.pointOnBody, direction));
      const double jt = std::min(speed / tangentDenominator, law.friction * jn);
      const btVector3 friction = direction * static_cast<btScalar>(jt);
      body.applyImpulse(friction, arm);
      total += friction;
      // Off the centre of mass, the friction impulse also turns the body and changes its normal
      // speed at the point; top the normal impulse up so the normal condition still holds exactly.
      const double vnAfter = static_cast<double>(n.dot(ropeVelocity - body.getVelocityInLocalPoint(arm)));
      if (vnAfter < vMin) {
        const btVector3 extra = n * static_cast<btScalar>(-(vMin - vnAfter) / normalDenominator);
        body.applyImpulse(extra, arm);
        total += extra;
      }
    }
  }
  body.activate();
  return total;
}

}  // namespace rope::bullet
