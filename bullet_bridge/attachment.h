#pragma once
// Attachments of a rope point C(s) to the world.
//  * to a rigid body's local point (two-way): a stiff implicit spring-damper on the rope's side
//    (Rod::addSpring with K = k I, D = c I, the body's predicted motion in f0 as for contacts), and the
//    equal and opposite impulse on the body, so a heavy body on a light rope (mass ratio 1000:1 and
//    more) stays stable: the light side is implicit, the heavy side sees the rope's finite stiffness.
//    The stiffness is capped on light bodies like a contact (contact_response.h: capForBody).
//  * to a fixed world point or a moving target: a rod pin (exact, Lagrange multiplier), whose target
//    can be moved every step.

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/contact_response.h"

namespace rope::bullet {

struct AttachmentSettings {
  double stiffness = 1.0e5;  // N/m, > 0: rope-to-body spring (the offset under load is force / stiffness)
  double damping = 50.0;     // N s/m, >= 0
  // Throws rope::InvalidArgument naming "attachment.stiffness" / "attachment.damping".
  void validate() const;
};

struct Attachment {
  int id = 0;
  double s = 0.0;                     // rope parameter
  btRigidBody* body = nullptr;        // nullptr: a pinned point (world point or moving target)
  btVector3 localPoint{0, 0, 0};      // in the body's frame (centre-of-mass frame), m
  AttachmentSettings settings;
  int pinId = 0;                      // the rod pin of a point attachment
  btVector3 lastForce{0, 0, 0};       // force on the rope in the last substep, N (body attachments)
  int bodyIndexHint = -1;             // where the body was last seen in its world's object array (world_membership.h)
};

// The rope side of a body attachment: f = -k (x_new - p_new) - c (u_new - v_p) with the body point
// predicted to move on at v_p (p_new = p + h v_p), in Rod::addSpring's form (see contact_response.h).
ContactSpring attachmentSpring(double stiffness, double damping, const Vec3& ropePoint, const Vec3& bodyPoint,
                               const Vec3& ropeVelocity, const Vec3& bodyVelocity, double h);

}  // namespace rope::bullet
