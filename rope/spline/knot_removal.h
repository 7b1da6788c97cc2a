// SPDX-License-Identifier: MIT
#pragma once
// Removal of one knot occurrence ([A] eq. 7; Tiller 1992; [B] §3.2 eq. 24 and Fig. 8).
//
// Removal inverts Boehm insertion: with the knot gone the curve has one control point less, and the
// insertion equations q_i = a_i p_i + (1 - a_i) p_{i-1} (i = k-d+1 .. k, on the knot vector *after*
// removal) are one more than the unknown p's. Solving them from the left leaves the last equation
// unsatisfied, solving from the right leaves the first: two candidates. Both are exact (and equal)
// when the curve really has the extra freedom; otherwise each moves the curve a little. The candidate
// with the smaller length error is chosen ([B]), and both errors are reported.
//
// Errors (metres):
//   shapeError  — max distance between the control points of the original curve and those of the
//                 candidate with the knot re-inserted; by the convex-hull property this bounds the
//                 largest displacement of the curve, max_s |C_new(s) - C_old(s)|.
//   lengthError — |L_new - L_old| of the arc length over the spans the removal touches, integrated
//                 over [s_{k-d}, s_{k+d+2}] of the knots before removal (clipped to the valid range),
//                 which holds the supports of every basis function whose coefficient the sweeps
//                 read or write; outside it the curves are identical, so this is the whole change.
//                 Same quadrature as arcLength() with default options.
// In floating point a sweep divides by a_i (left) or 1 - a_i (right): when the knot is removable
// the stable side reproduces the curve to rounding and the other may show amplified rounding in
// its errors; the smaller length error then picks the stable side (checked on 1000 random
// insert-then-remove cases in the tests, not proven).

#include <array>
#include <vector>

#include "rope/common/types.h"
#include "rope/spline/knot_vector.h"

namespace rope {

struct KnotRemoval {
  enum Side { kFromLeft = 0, kFromRight = 1 };

  double parameter = 0.0;  // the removed knot value
  int knotIndex = 0;       // index of the removed occurrence in the knot vector before removal
  int span = 0;            // k: span of the parameter in the knot vector after removal
  int degree = 0;
  int multiplicityAfter = 0;  // multiplicity of the knot value after removal
  // alpha[j] = a_{k-d+1+j} on the knot vector after removal (as in KnotInsertion).
  std::array<double, kMaxDegree> alpha{};

  Side chosen = kFromLeft;                  // the side with the smaller length error
  std::array<double, 2> shapeError{};       // per side, metres
  std::array<double, 2> lengthError{};      // per side, metres
  double chosenShapeError() const { return shapeError[chosen]; }
  double chosenLengthError() const { return lengthError[chosen]; }

  // Applies the sweep of one side (default: the chosen one) to per-control-point values
  // (positions, velocities, ...): values shrinks by one. The sweep is linear in the values, so
  // velocities follow the same map as positions. Values: a std::vector (or any container with its
  // value_type, operator[], begin() and erase()).
  template <class Values>
  void apply(Values& values) const { apply(values, chosen); }
  template <class Values>
  void apply(Values& values, Side side) const;
};

// Plans the removal of one occurrence of the knot s (the last one) without changing anything.
// Throws InvalidArgument: "s" NaN or not a knot value strictly inside the valid range; "points.size()"
// not matching the knots or leaving fewer than degree+1 control points after removal.
KnotRemoval planKnotRemoval(const KnotVector& knots, const PointList& points, double s);

// The same plan with the shape errors of both sides only (lengthError left at 0 and chosen at
// kFromLeft): about a tenth of the cost, since the length errors integrate the arc length over 2d+2
// spans. min(shapeError) bounds the chosen side's shape error from below, so a removal whose
// min(shapeError) exceeds a bound can be rejected on this alone.
KnotRemoval planKnotRemovalShape(const KnotVector& knots, const PointList& points, double s);

// Plans and applies the chosen candidate to knots and points together. All-or-nothing.
KnotRemoval removeKnot(KnotVector& knots, PointList& points, double s);

// ---- implementation of the template ----
template <class Values>
void KnotRemoval::apply(Values& values, Side side) const {
  using T = typename Values::value_type;
  // Unknowns p_i for i in [first, last]; p_{first-1} = q_{first-1} and p_{last+1} = q_{last+2} are
  // kept. Equations i = first .. last+1 use alpha[i - first].
  const int d = degree;
  const int first = span - d + 1;
  const int last = span - multiplicityAfter - 1;  // may be < first: nothing to solve
  auto a = [&](int i) { return alpha[static_cast<size_t>(i - first)]; };
  auto at = [&](int i) -> T& { return values[static_cast<size_t>(i)]; };
  if (last >= first) {
    if (side == kFromLeft) {
      for (int i = first; i <= last; ++i) at(i) = (at(i) - (1.0 - a(i)) * at(i - 1)) * (1.0 / a(i));
    } else {
      // p_{i-1} = (q_i - a_i p_i) / (1 - a_i), from i = last+1 down to first+1; p_{last+1} is q_{last+2}.
      // q_{i-1} is read before its slot receives p_{i-1}.
      T right = at(last + 2);
      T q = at(last + 1);
      for (int i = last + 1; i >= first + 1; --i) {
        const T qPrevious = at(i - 1);
        const T p = (q - a(i) * right) * (1.0 / (1.0 - a(i)));
        at(i - 1) = p;
        right = p;
        q = qPrevious;
      }
    }
  }
  // The surplus equation's point q_{last+1} (left) or q_{first} shifted (right) leaves the array:
  // after the sweep, indices first..last hold the unknowns in both cases; drop index last+1.
  values.erase(values.begin() + (last + 1));
}

}  // namespace rope
