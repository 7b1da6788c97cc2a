#pragma once
// One-way contact of a kinematic rope on a dynamic body: the rope is moved by its driver and is never
// pushed back, so the contact is resolved on the body alone, as against an infinitely heavy pusher.
//
// With n the contact normal (from the body into the rope, contact.h), d the signed distance, v_r the
// rope's velocity at the contact and v_b the body's velocity at its contact point, the relative
// normal speed is v_n = n.(v_r - v_b) (< 0: approaching). The body gets the normal impulse
//   j_n = max(0, v_min - v_n) / (n.K n),   v_min = -d / h            for d >= 0 (speculative),
//                                          v_min = -recovery d / h   for d < 0  (penetrating),
// along -n at its contact point (K the body's impulse matrix there, computeImpulseDenominator), so
// after it the gap closes at most to zero within the next substep, and a penetration shrinks by the
// fraction `recovery` per substep. Then a Coulomb friction impulse of at most friction * j_n drags the
// contact point towards the rope's tangential velocity (off the centre of mass it also turns the
// body, so the normal impulse is topped up if that made the normal speed fall below v_min again).
// All are exact velocity changes at the body's effective mass, hence stable for any mass and step.

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/contact.h"

namespace rope::bullet {

struct OneWayContactLaw {
  double penetrationRecovery = 0.2;  // in (0, 1], fraction of the depth removed per substep
  double friction = 0.3;             // Coulomb coefficient, >= 0
};

// Applies the impulse above to `body` (which must be dynamic: inverse mass > 0) and wakes it.
// ropeVelocity in m/s, h in s (> 0). Returns the total impulse given to the body (N s, world frame;
// zero when the contact is separating fast enough). The caller guarantees finite input.
btVector3 applyOneWayContact(btRigidBody& body, const Contact& contact, const btVector3& ropeVelocity, double h,
                             const OneWayContactLaw& law);

}  // namespace rope::bullet
