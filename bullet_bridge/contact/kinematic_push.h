// SPDX-License-Identifier: MIT
#pragma once
// One-way contact of a kinematic rope on a dynamic body: the rope is moved by its driver and is never
// pushed back, so the contacts are resolved on the body alone, as against an infinitely heavy pusher.
//
// For a contact with normal n (from the body into the rope, contact.h), signed distance d, rope
// velocity v_r and body point velocity v_b, the relative normal speed is
//   v_n = n.(v_r - v_b - g h)    (< 0: approaching),
// where g h is the gravity increment Bullet will add to the body's velocity before it next moves it
// (the rope acts after a substep's integration; without it a body resting on the rope would fall
// g h^2 and be pushed back every substep). The contacts of one body are solved together by projected
// Gauss-Seidel on accumulated impulses, like Bullet's own solver: each contact's normal impulse
// j_n >= 0 brings v_n up to
//   v_min = -d / h               for d >= 0 (speculative: the gap may close, not be passed),
//   v_min = -recovery * d / h    for d < 0  (a penetration shrinks by `recovery` per substep),
// and a friction impulse j_t, |j_t| <= friction * j_n, drags the body's contact point towards the
// rope's tangential velocity. Every update is an exact velocity change at the body's effective mass
// at the contact (computeImpulseDenominator), so the scheme is stable for any mass and step. A body
// resting on a rope holds its position; its velocity read between steps is then the upward g h that
// the next substep's gravity cancels, rather than zero.
// Not API: installed only because kinematic_rope.h holds its contacts; it may change in any release.

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/contact.h"

namespace rope::bullet {

struct OneWayContactLaw {
  double penetrationRecovery = 0.2;  // in (0, 1], fraction of the depth removed per substep
  double friction = 0.3;             // Coulomb coefficient, >= 0
  int iterations = 10;               // Gauss-Seidel sweeps over one body's contacts, >= 1
};

struct OneWayContact {
  Contact contact;                         // body-rope contact (contact.h conventions)
  btVector3 ropeVelocity{0, 0, 0};         // m/s, the rope's velocity at the contact
  double normalImpulse = 0.0;              // N s, out: accumulated j_n >= 0 (applied along -normal)
  btVector3 frictionImpulse{0, 0, 0};      // N s, out: accumulated tangential impulse on the body
  btVector3 impulse() const { return frictionImpulse - contact.normal * static_cast<btScalar>(normalImpulse); }
};

// Solves and applies the impulses of `count` contacts on `body` (dynamic: inverse mass > 0) and wakes
// it. h in s (> 0). The caller guarantees finite input; contacts' outputs are overwritten.
void solveOneWayContacts(btRigidBody& body, OneWayContact* contacts, int count, double h, const OneWayContactLaw& law);

}  // namespace rope::bullet
