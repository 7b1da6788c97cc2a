// SPDX-License-Identifier: MIT
#pragma once
// Knot insertion without a rise in the internal energy (docs/method.md §10, "Insertion and energy",
// eq. 29a; beyond [A]).
//
// Inserting a knot keeps the curve, its velocity field and the rest curve exactly ([A] eq. 6), so the
// kinetic, gravity and bending energies are unchanged. The locking-free stretching rule
// (StretchingQuadrature::kLockingFree) is not: it samples the strain at one point per span, and a
// strain that varies inside a span around the sampled value holds no energy until the new knot's
// points sample it. Measured on an undamped 1 m rope swinging down from horizontal (6 control points):
// one step's two insertions raised the stretching energy from 1.8e-4 J to 6.6e-2 J (13 % of m g L/2);
// the exactly integrated energy of the same curve was 6.0e-2 J. The strain is real in the curve, but
// the coarser rope never resisted it, so the energy it would now store was never given to the rope.
//
// relaxInsertion gives that energy back: the control points whose basis functions reach the new spans
// move by the least lumped-mass-weighted displacement that brings the internal energy (stretching +
// bending) back to its value before the insertion, while
//   - sum_a g_a dq_a = 0, g_a = mu int b_a l0' ds (plus point masses m b_a(s)): the centre of mass and
//     the gravity energy (linear in q) are exactly unchanged;
//   - pinned points C(s_p), and a clamp's tangent direction, are exactly unchanged (their rows on dq);
//   - velocities are not touched: momentum and kinetic energy are exactly unchanged.
// So the total energy after the insertion is at most its value before. The displacement is searched on
// the Levenberg–Marquardt path of the energy's quadratic model restricted to those conditions,
// dq(lambda) = -lambda (W + lambda H)^-1 grad E (W the lumped masses, H the Gauss–Newton stiffness;
// lambda in s^2: one implicit relaxation step of squared length lambda), from the mass-weighted
// gradient at small lambda to the Newton step at large lambda, with lambda bisected on a log scale
// against the true energy. Work: dense O(d^3) algebra on the O(d) spans the moved points reach.
#include <vector>

#include "rope/common/types.h"
#include "rope/rod/pin_constraints.h"
#include "rope/rod/rod_integrals.h"

namespace rope {

struct InsertionRelaxation {
  double excess = 0.0;         // J: internal energy after the insertion minus before (<= 0: nothing done)
  double remaining = 0.0;      // J: what is left above the energy before (0 when reached)
  double displacement = 0.0;   // m: largest control-point displacement applied
  int iterations = 0;          // paths built (one per Newton rebuild, over all windows)
};

// Moves points[first..last] (clamped to the rod) so that the internal energy falls by `excess` J
// (see above); where pins, a clamp or an end leave those points too little freedom, the window widens
// by one point on each side, up to three times. `rows`: linear conditions on the displacement that
// must stay zero (pins' and clamps' rows; their right-hand sides are ignored). pointMasses: (s, kg)
// carried by the rod. axialStiffness EA in N. Does nothing for excess <= 0.
InsertionRelaxation relaxInsertion(const KnotVector& knots, const RodIntegrals& integrals,
                                   double axialStiffness, double excess, int first, int last,
                                   const std::vector<ConstraintRows>& rows,
                                   const std::vector<std::pair<double, double>>& pointMasses,
                                   PointList& points);

}  // namespace rope
