// SPDX-License-Identifier: MIT
#pragma once
// Attachments of a rope point C(s) to the world.
//  * to a rigid body's local point (two-way): a stiff implicit spring-damper on the rope's side
//    (Rod::addSpring with K = k I, D = c I, the body's predicted motion in f0 as for contacts), and the
//    equal and opposite impulse on the body, so a heavy body on a light rope (mass ratio 1000:1 and
//    more) stays stable: the light side is implicit, the heavy side sees the rope's finite stiffness.
//    The stiffness is capped on light bodies like a contact (contact_response.h: capForBody).
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
#include "bullet_bridge/contact_response.h"

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
  int bodyIndexHint = -1;             // where the body was last seen in its world's object array (world_membership.h)
};

// The rope side of a body attachment: f = -k (x_new - p_new) - c (u_new - v_p) with the body point
// predicted to move on at v_p (p_new = p + h v_p), in Rod::addSpring's form (see contact_response.h).
ContactSpring attachmentSpring(double stiffness, double damping, const Vec3& ropePoint, const Vec3& bodyPoint,
                               const Vec3& ropeVelocity, const Vec3& bodyVelocity, double h);
// The same with 3x3 stiffness (N/m) and damping (N s/m), symmetric positive semidefinite.
ContactSpring attachmentSpring(const Eigen::Matrix3d& stiffness, const Eigen::Matrix3d& damping, const Vec3& ropePoint,
                               const Vec3& bodyPoint, const Vec3& ropeVelocity, const Vec3& bodyVelocity, double h);

// The attachment spring on a dynamic body, capped for the body's explicit impulse: along each
// principal direction of the point's inverse-mass matrix W (m/(N s^2): the velocity change of the
// body point per unit impulse, W = I/m - [r]x I^-1 [r]x, r the arm from the centre of mass) the
// stiffness is at most share / (h^2 lambda) and the damping share / (h lambda). Direction by direction
// rather than with the smallest effective mass overall: a ball hanging from a point on its surface is
// light sideways (it turns) but its full mass along the arm, which is where the load pulls (a 10 kg ball
// at 1/240 s: 1e5 N/m kept along the rope instead of 4.1e4, so the ball sits 1 mm off the rope's end
// rather than 2.4 mm). Uncapped, the result is exactly stiffness I and damping I.
void capAttachmentForBody(const Eigen::Matrix3d& inverseMass, double h, double share, double stiffness,
                          double damping, Eigen::Matrix3d& stiffnessOut, Eigen::Matrix3d& dampingOut);

// The rope side of a clamp's rotational spring, on C'(s) in Rod::addTangentSpring's form: with g =
// C'/l0' (the stretch times the unit tangent), d the body's direction turning at omega, and
// P = I - d d^T, E = (k/2) |P g|^2, so f = -(k / l0'^2) P C' - (c / l0'^2) P (Cdot' - omega x C')
// + (k h / l0'^2) P (omega x C') (the body turns on during the step, as the point spring's target
// moves), K = (k / l0'^2) P, D = (c / l0'^2) P.
ContactSpring clampTangentSpring(double stiffness, double damping, double restMetric, const Vec3& derivative,
                                 const Vec3& derivativeRate, const Vec3& direction, const Vec3& angularVelocity,
                                 double h);

}  // namespace rope::bullet
