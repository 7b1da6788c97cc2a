// SPDX-License-Identifier: MIT
#pragma once
// Penalty contact with damping and Coulomb friction, linearised for the rope's implicit step
// (Rod::addSpring) and closed by Newton's third law.
//
// The point law (rope-rope contact, rope_rope_contact.h), at the end of the step (backward Euler, as
// the rod's own forces), with gap d, unit normal n into the rope, rope velocity u, the other side's
// velocity v_b and w = u - v_b:
//   f_n = -k d_new - c n.w_new,   d_new = d + h n.(u_new - v_b)          (normal, along n)
//   f_t = -eta P_t w_new,         eta = mu f_n0 / max(|P_t w|, v_reg)   (tangent, P_t = I - n n^T)
// so |f_t| <= mu f_n0 when sliding at a steady speed, and below v_reg the friction is a stiff viscous
// "stick" that stays stable because it is implicit. f_n0 = max(0, normal force at the current state).
// In Rod::addSpring's form f ~ f0 - K (x_new - x) - D (u_new - u) this is K = k n n^T,
// D = c n n^T + eta P_t and f0 = (-k d - c n.w + k h n.v_b) n - eta P_t w (the k h n.v_b term lets
// the body move on during the step). Rope-body contact uses the samples' law below instead.
//
// The rope then feels exactly F = f0 - h K u_new - D (u_new - u) over the step (what the rod's system
// integrates); endOfStepForce() rebuilds it from the rope's new velocity at s, and the other side gets
// -F h at the contact point, so the pair conserves linear momentum to round-off.

#include <Eigen/Core>

#include "rope/common/types.h"

// Not API: installed only because attachment.h and rope_rope_contact.h include it; may change in any release.
namespace rope::bullet {

struct ContactLaw {
  double stiffness = 0.0;           // k, N/m
  double damping = 0.0;             // c, N s/m
  double speculativeDamping = 0.0;  // c_s, N s/m: normal law of a contact that is still apart
  double friction = 0.0;            // mu
  double frictionVelocity = 1e-3;   // v_reg, m/s
  double frictionDampingLimit = 1e300;  // cap on eta, N s/m (explicit stability on light bodies)
};

struct ContactSpring {
  Vec3 force = Vec3::Zero();                           // f0, N
  Eigen::Matrix3d stiffness = Eigen::Matrix3d::Zero(); // K, N/m
  Eigen::Matrix3d damping = Eigen::Matrix3d::Zero();   // D, N s/m
};

// The linearised law for a contact at gap `distance` (m, < 0 penetrating) over a step of h seconds.
// frictionNormalForce (N): the normal force that bounds friction; negative means "the penetration
// force at the current state", max(0, -k d). RopeObject passes the normal force the contact came out
// with in a previous solve of the same substep (see the header comment).
ContactSpring contactSpring(const ContactLaw& law, double distance, const Vec3& normal, const Vec3& ropeVelocity,
                            const Vec3& bodyVelocity, double h, double frictionNormalForce = -1.0);

// Whether a contact acts in this step: penetrating now, or its gap is predicted to close within the
// step at the current relative velocity (d + h n.(u - v_b) < 0). A speculative contact (d > 0) that
// acts starts from f0 = -k d n, i.e. it holds the rope at the surface rather than before it. Gravity
// is left out of the prediction on purpose: it would activate the many near-touching contacts of a
// resting rope with that small pull, which inflates their friction bound.
bool contactActive(double distance, const Vec3& normal, const Vec3& ropeVelocity, const Vec3& bodyVelocity, double h);

// The force the rope felt over the step (see the header comment), from its velocity at s before
// (u) and after (uNew) the step.
Vec3 endOfStepForce(const ContactSpring& spring, const Vec3& u, const Vec3& uNew, double h);

// ---- line-contact samples (line_contact.h; docs/method.md §11, eqs. 31-34) ----
// One sample of a rope-body line contact carries the normal law above with the sample's share of the
// line law (stiffness = lineContactStiffness * weight, ...), and Coulomb friction with a stick state
// instead of the regularised law:
//  * sticking: a tangential spring of the same stiffness and damping to the sample's anchor a (the body
//    point where it began to stick, friction_anchors.h), f_t = -k P_t (x_new - a_new) - c P_t w_new,
//    with a_new = a + h v_b: implicit, so a rope held on a slope or around a post does not creep;
//  * sliding: exactly mu f_n against the slip direction d, f_t = -mu f_n d(w_new), linearised about the
//    slip speed |w_t| (implicit in the direction, D = mu f_n / |w_t| (P_t - d d^T), exact in magnitude),
//    so a sliding rope feels Coulomb's force at every speed, not a viscous ramp up to it.
// RopeObject's active set switches a sticking sample whose end-of-step spring force exceeds mu f_n to
// sliding, in the direction of that force.
struct SampleFriction {
  bool sliding = false;
  Vec3 displacement = Vec3::Zero();  // sticking: P_t (x - a) at the start of the step, m
  Vec3 direction = Vec3::Zero();     // sliding: unit tangent, the rope's slip relative to the body
  double speed = 1.0;                // sliding: slip speed the direction is linearised at, m/s, > 0
  double normalForce = 0.0;          // sliding: the normal force bounding friction, N, >= 0
};

// law.friction is mu; law.frictionVelocity is not used (see SampleFriction).
ContactSpring sampleSpring(const ContactLaw& law, double distance, const Vec3& normal, const Vec3& ropeVelocity,
                           const Vec3& bodyVelocity, double h, const SampleFriction& friction);

// Caps a stiffness (N/m) and damping (N s/m) acting on a body of effective mass 1 / inverseMass (kg)
// to share * the explicit stability limits m / h^2 and m / h; inverseMass == 0 leaves them unchanged.
void capForBody(double inverseMass, double h, double share, double& stiffness, double& damping);

}  // namespace rope::bullet
