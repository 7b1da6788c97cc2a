// SPDX-License-Identifier: MIT
#pragma once
// Green–Lagrange stretching ([A] eqs. 11–12; docs/method.md §6, eqs. 13–17):
//   E = (EA/8) int (gamma^2 - 1)^2 l0' ds,  gamma = |C'(s)| / l0'(s),
//   F_i = (EA/2) sum_m q_m [B_im - sum_pq B_impq q_p.q_q],
//   K_im = (EA/2) [(sum_pq B_impq q_p.q_q - B_im) I + 2 sum_ac B_imac q_a q_c^T]   (exact Hessian).
// In the factored form of rod_integrals.h, at each Gauss point with t = W3 |C'|^2 - W1
// (= w J (gamma^2 - 1) / l0'), the point contributes F_a = -(EA/2) t b'_a C' and
// K_ab = b'_a b'_b [(EA/2) t I + EA W3 C' C'^T].
// The kernel works on whatever points the integrals hold: the exact rule (method §7) or the
// locking-free reduced rule (StretchingQuadrature in rod_settings.h); force and stiffness are always
// the exact derivatives of the energy as sampled.
// Under compression (t < 0) the first term makes K indefinite; the Gauss–Newton clamp replaces t by
// max(t, 0) there (method eq. 17: drop the negative part), which leaves K positive semidefinite, so that
// M + hD + h^2 K stays positive definite. The exact Hessian is kept for tests and diagnostics.

#include <Eigen/Core>

#include "rope/common/types.h"
#include "rope/rod/banded_matrix.h"
#include "rope/rod/rod_integrals.h"

namespace rope {

enum class StiffnessMode { kExact, kClamped };

// One span: q points at the span's d+1 control points. Adds the forces to force[0..d] (if force is
// not null) and, if stiffness is not null, writes the lower blocks stiffness[a * (d+1) + b], a >= b. Returns the energy (J).
double stretchingSpan(const SpanView& span, const Vec3* q, double axialStiffness, StiffnessMode mode,
                      Vec3* force, Eigen::Matrix3d* stiffness);

// One span's material stiffness, the lower blocks b'_a b'_b EA W3 C' C'^T (K without its tension
// term), evaluated with the tangent of q. It maps velocities to the rate of the strain measure,
// d(W3 |C'|^2)/dt = 2 W3 C'.v', so materialDamping times it is Kelvin–Voigt damping (method eq. 20):
// zero on rigid motion, positive semidefinite. Evaluated at the midpoint of a step's start and end it
// gives the step's strain change exactly (the strain is quadratic in q).
void materialStiffnessSpan(const SpanView& span, const Vec3* q, double axialStiffness, Eigen::Matrix3d* stiffness);

// Whole-rod forms (O(n)); EA in N.
double stretchingEnergy(const RodIntegrals& integrals, const PointList& q, double axialStiffness);
// forces is resized to q.size() and overwritten.
void stretchingForces(const RodIntegrals& integrals, const PointList& q, double axialStiffness,
                      PointList& forces);
// K is reset to q.size() blocks of 3 with block bandwidth d and filled.
void assembleStretchingStiffness(const RodIntegrals& integrals, const PointList& q,
                                 double axialStiffness, StiffnessMode mode, SymmetricBandedMatrix& K);
// Largest gamma - 1 over the Gauss points (dimensionless engineering strain; negative if compressed
// everywhere).
double maxStrain(const RodIntegrals& integrals, const PointList& q);

}  // namespace rope
