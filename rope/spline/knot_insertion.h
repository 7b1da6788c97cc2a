// SPDX-License-Identifier: MIT
#pragma once
// Boehm's single-knot insertion ([A] §3.1 eqs. 2–6; docs/method.md §2). Inserting s* into span k
// (s_k <= s* < s_{k+1}) replaces q_{k-d+1..k} by
//   q'_i = a_i q_i + (1 - a_i) q_{i-1},   a_i = (s* - s_i) / (s_{i+d} - s_i),
// keeps q'_i = q_i for i <= k-d and shifts q'_{i+1} = q_i for i >= k. The curve is exactly unchanged.
// The plan depends on the knots only and is linear in the control points, so applying the same plan
// to velocities (or any per-control-point quantity) keeps the velocity field C'(s,t) unchanged too.

#include <array>
#include <vector>

#include "rope/common/types.h"
#include "rope/spline/knot_vector.h"

namespace rope {

struct KnotInsertion {
  double parameter = 0.0;  // s*
  int span = 0;            // k, in the knot vector before insertion
  int degree = 0;
  // alpha[j] = a_{k-d+1+j} for j = 0 .. d-1.
  std::array<double, kMaxDegree> alpha{};

  // First and last control point index (after insertion) whose value is a new combination.
  int firstChanged() const { return span - degree + 1; }
  int lastChanged() const { return span; }

  // Applies the map to per-control-point values (positions, velocities, rest positions, ...):
  // values grows by one. Values: a std::vector (or any container with its value_type, operator[],
  // begin() and insert()) of a T with T*double and T+T (double, Vec3, Eigen vectors).
  template <class Values>
  void apply(Values& values) const {
    using T = typename Values::value_type;
    const int first = firstChanged();
    // Duplicate q_k: the copy at k+1 is q'_{k+1} = q_k, everything after it shifts by one.
    const T duplicate = values[static_cast<size_t>(span)];
    values.insert(values.begin() + span, duplicate);
    // Walk from the right so that q_{i-1} is still the old value when q'_i is formed.
    for (int i = span; i >= first; --i) {
      const double a = alpha[static_cast<size_t>(i - first)];
      values[static_cast<size_t>(i)] = a * values[static_cast<size_t>(i)] +
                                       (1.0 - a) * values[static_cast<size_t>(i - 1)];
    }
  }
};

// Plans the insertion of s without changing anything. Throws InvalidArgument("s", ...) for NaN,
// s not strictly inside the valid range, or s whose multiplicity would exceed degree+1.
KnotInsertion planKnotInsertion(const KnotVector& knots, double s);

// Inserts s into knots and points together (points.size() must equal knots.controlPointCount(),
// "points.size()"); returns the plan so that other arrays can follow. All-or-nothing.
KnotInsertion insertKnot(KnotVector& knots, PointList& points, double s);

}  // namespace rope
