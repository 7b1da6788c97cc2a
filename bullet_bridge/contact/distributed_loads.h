// SPDX-License-Identifier: MIT
#pragma once
// Loads spread along a stretch of rope, turned into the rod's consistent generalised forces by
// Gauss–Legendre quadrature over the knot spans: a load q(s) per metre of rope gives control point i
// the force F_i = int b_i(s) q(s) dl, dl the rope's length element, sampled at degree + 1 points per
// span (exact for a cubic basis times a linear load). Each sample is queued as a spring sample of the
// rod (Rod::addSpringSample: a load, no knot), so it acts in the next step like Rod::addForce.
//
//  * A user's distributed force (RopeObject::applyDistributedForce): q per metre of rest length (a
//    load on the material, as gravity is), dl = l0'(s) ds.
//  * Aerodynamic drag (BulletRopeSettings::fluidDensity, ...): with w = Cdot(s) - wind the velocity
//    relative to the fluid, t the unit tangent, w_t = (w.t) t and w_n = w - w_t, the Morison-type
//    quadratic law per metre of current length (dl = |C'(s)| ds)
//        q = -c_n |w_n| w_n - c_t |w_t| w_t,   c_n = rho d C_n / 2,   c_t = rho pi d C_t / 2
//    (d = 2 r; C_n the cylinder's cross-flow drag coefficient on its projected area d per metre,
//    C_t the skin-friction coefficient on its wetted area pi d per metre). It is queued with its
//    velocity Jacobian D = -dq/dw = c_n (|w_n| P_n + w_n w_n^T / |w_n|) + 2 c_t |w.t| t t^T (symmetric,
//    positive semidefinite), so the rod's backward-Euler step treats it implicitly: q_new ~ q - D
//    (u_new - u), one Newton step of the drag per substep, stable at any speed and exact at the
//    terminal velocity (where u_new = u).
// Internal to the bridge (not installed).

#include "rope/common/types.h"

namespace rope {
class Rod;
}

namespace rope::bullet {

// Queues int_{s0}^{s1} b_i(s) q l0'(s) ds on the rod for its next step. The caller has validated
// beginParameter <= s0 < s1 <= endParameter and q finite; nothing is queued if it throws.
void queueDistributedForce(Rod& rod, double s0, double s1, const Vec3& forcePerLength);

struct DragLaw {
  double normal = 0.0;      // c_n, kg/m^2 (N per metre of rope per (m/s)^2)
  double tangential = 0.0;  // c_t, kg/m^2
  Vec3 wind = Vec3::Zero(); // m/s
  bool active() const { return normal > 0.0 || tangential > 0.0; }
};

// The drag over the whole rope at its current state, queued for the next step (see the header).
void queueDrag(Rod& rod, const DragLaw& law);

}  // namespace rope::bullet
