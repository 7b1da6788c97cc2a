// SPDX-License-Identifier: MIT
#pragma once
// Bending (beyond [A], which had stretching only):
//   E_b = (1/2) int EI |C''(s)|^2 / l0'(s)^3 ds.
// Why this form: with the rest arclength sigma (d sigma = l0' ds) and a rest parametrisation at constant
// speed, d^2C/d sigma^2 = C'' / l0'^2, and for a nearly inextensible rope its length is the curvature;
// so E_b = (1/2) int EI kappa^2 d sigma, the Euler–Bernoulli / Kirchhoff bending energy of a naturally
// straight rope, in its linearised ("curve parametrised near arclength") form. It is defined on the
// continuous curve (resolution independent: knot insertion leaves it unchanged), and it is quadratic in
// the control points, so its stiffness is a constant banded matrix K_b = EI int b_i'' b_m'' / l0'^3 ds
// (times I_3) that changes only when the knots do, and it never makes the system indefinite. The exact
// curvature |C' x C''| / |C'|^3 would be geometrically exact under stretching but non-convex, costly,
// and singular where C' -> 0; for ropes (strain << 1) the difference is O(strain). It also penalises
// changes of stretch along the rope (the tangential part of C''), again an O(strain) effect.
// It has no torsion: ropes here carry no twist.

#include "rope/common/types.h"
#include "rope/rod/banded_matrix.h"
#include "rope/rod/rod_integrals.h"

namespace rope {

// One span: q points at the span's d+1 control points. If force is not null, adds -dE/dq to
// force[0..d]. Returns sum plus the span's energy (J), term by term, so that the whole-rod energy is
// one running sum over all spans (the same rounding whether summed here or by a caller).
double bendingSpan(const SpanView& span, const Vec3* q, Vec3* force, double sum = 0.0);
// J (the integrals carry EI).
double bendingEnergy(const RodIntegrals& integrals, const PointList& q);
// forces resized to q.size() and overwritten with -K_b q.
void bendingForces(const RodIntegrals& integrals, const PointList& q, PointList& forces);
// K_b as a scalar banded matrix (block size 1, bandwidth d); the 3D stiffness is K_b (x) I_3.
void assembleBendingStiffness(const RodIntegrals& integrals, int controlPointCount,
                              SymmetricBandedMatrix& K);

}  // namespace rope
