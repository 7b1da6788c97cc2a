// SPDX-License-Identifier: MIT
#pragma once
// Attachments of a rope point C(s) to the world.
//  * to a rigid body's local point (two-way): a stiff implicit spring-damper on the rope's side
//    (Rod::addSpring with K = k I, D = c I, the body's predicted motion in f0 as for contacts), and the
//    equal and opposite impulse on the body, so a heavy body on a light rope (mass ratio 1000:1 and
//    more) stays stable: the light side is implicit, the heavy side sees the rope's finite stiffness.
//    On a dynamic body the spring acts in series with the body's inertia (seriesWithBody).
//  * clamped to a rigid body (a weld: RopeObject::clampToBody): the point spring above, plus a
//    rotational spring that holds the rope's tangent at s along a direction fixed in the body. On the
//    rope it is implicit (Rod::addTangentSpring on C'(s)/l0'(s), stiffness k_r P, P = I - d d^T the
//    projector across the direction d); the body gets the opposite moment -(C' x f) as an explicit
//    angular impulse, with k_r and c_r capped on light bodies against the body's smallest principal
//    moment of inertia as the point spring is against its mass.
//  * to a fixed world point or a moving target: a rod pin (exact, Lagrange multiplier), whose target
//    can be moved every step.

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/contact/contact_response.h"

namespace rope::bullet {

struct AttachmentSettings {
  double stiffness = 1.0e5;  // N/m, > 0: rope-to-body spring (the offset under load is force / stiffness)
  double damping = 50.0;     // N s/m, >= 0
  // Clamps only (clampToBody): the rotational spring holding the tangent, N m/rad, > 0 (the angle
  // error under a moment M is M / angularStiffness: 1e-4 rad at 1 N m), and its damping, N m s/rad,
  // >= 0. Stable at any value on the rope's side (implicit); capped on light bodies.
  double angularStiffness = 1.0e4;
  double angularDamping = 1.0;
  // Throws rope::InvalidArgument naming "attachment.stiffness" / "attachment.damping".
  void validate() const;
};

struct Attachment {
  int id = 0;
  double s = 0.0;                     // rope parameter
  btRigidBody* body = nullptr;        // nullptr: a pinned point (world point or moving target)
  btVector3 localPoint{0, 0, 0};      // in the body's frame (centre-of-mass frame), m
  bool clamp = false;                 // clampToBody: the tangent is held along localDirection too
  btVector3 localDirection{0, 0, 0};  // clamps: unit, in the body's frame
  AttachmentSettings settings;
  int pinId = 0;                      // the rod pin of a point attachment
  btVector3 lastForce{0, 0, 0};       // force on the rope in the last substep, N (body attachments)
  btVector3 lastMoment{0, 0, 0};      // clamps: moment on the rope in the last substep, N m
  int bodyIndexHint = -1;             // where the body was last seen in its world's object array (detail/world_membership.h)
};

// The rope side of a body attachment: f = -k (x_new - p_new) - c (u_new - v_p) with the body point
// predicted to move on at v_p (p_new = p + h v_p), in Rod::addSpring's form (see contact/contact_response.h).
ContactSpring attachmentSpring(double stiffness, double damping, const Vec3& ropePoint, const Vec3& bodyPoint,
                               const Vec3& ropeVelocity, const Vec3& bodyVelocity, double h);

// The attachment spring to a dynamic body, with the body's response made implicit: the body point's
// velocity changes by W (-f h) when the rope pulls with f (W = I/m - [r]x I^-1 [r]x, m/(N s^2), the
// point's inverse-mass matrix, r the arm from the centre of mass), and f is the spring's force at the
// end of the step with the body point where that impulse takes it:
//   f = -k (x_new - p - h v_p') - c (u_new - v_p'),  v_p' = v_p - h W f
// which is the spring of attachmentSpring() premultiplied by A^-1, A = I + (h^2 k + h c) W: a spring in
// series with the body's inertia. The rope's side stays implicit and the body gets exactly -f h, so no
// stiffness cap is needed for stability (a contact's explicit impulse needs capForBody), and a heavy
// load hangs off the rope by its weight / stiffness, not by a capped stiffness. v_p includes the
// body's own forces over the step (pointAccelerationFromForces: its weight), so a 10 kg ball on the
// default 1e5 N/m sits W / k = 0.98 mm off the rope's end at 1/60 s (3.7 mm without them, 1.1 cm
// with a capped spring).
// W = 0 (a static or kinematic body) leaves the spring as it is.
void seriesWithBody(ContactSpring& spring, const Eigen::Matrix3d& inverseMass, double h);

// The rope side of a clamp's rotational spring, on C'(s) in Rod::addTangentSpring's form: with g =
// C'/l0' (the stretch times the unit tangent), d the body's direction turning at omega, and
// P = I - d d^T, E = (k/2) |P g|^2, so f = -(k / l0'^2) P C' - (c / l0'^2) P (Cdot' - omega x C')
// + (k h / l0'^2) P (omega x C') (the body turns on during the step, as the point spring's target
// moves), K = (k / l0'^2) P, D = (c / l0'^2) P.
ContactSpring clampTangentSpring(double stiffness, double damping, double restMetric, const Vec3& derivative,
                                 const Vec3& derivativeRate, const Vec3& direction, const Vec3& angularVelocity,
                                 double h);

}  // namespace rope::bullet
