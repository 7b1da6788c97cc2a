// SPDX-License-Identifier: MIT
#pragma once
// Splitting a curve in two ([A] §5.1; docs/method.md §4): raising the multiplicity of s to d+1 by exact knot
// insertion makes the curve C^-1 there, so no basis function spans s any more. The two sides then
// share no mass, energy or force terms and become two independent curves that meet at C(s).

#include <utility>
#include <vector>

#include "rope/common/types.h"
#include "rope/spline/knot_insertion.h"
#include "rope/spline/knot_vector.h"

namespace rope {

struct CurveSplitPlan {
  double parameter = 0.0;
  // Insertions that raise s to multiplicity degree+1, in order (possibly none).
  std::vector<KnotInsertion> insertions;
  KnotVector leftKnots;   // knots of the left piece, valid range [validBegin, s]
  KnotVector rightKnots;  // knots of the right piece, valid range [s, validEnd]
  // After the insertions, control points [0, rightFirstPoint) belong to the left piece and
  // [rightFirstPoint, end) to the right one.
  int rightFirstPoint = 0;

  // Applies the insertions to per-control-point values and cuts them (positions, velocities, ...).
  template <class T>
  std::pair<std::vector<T>, std::vector<T>> apply(std::vector<T> values) const {
    for (const KnotInsertion& insertion : insertions) insertion.apply(values);
    std::vector<T> right(values.begin() + rightFirstPoint, values.end());
    values.resize(static_cast<size_t>(rightFirstPoint));
    return {std::move(values), std::move(right)};
  }
};

// Depends on the knots only. Throws InvalidArgument("s", ...) for NaN or s not strictly inside the
// valid range (splitting at an end is an error).
CurveSplitPlan planCurveSplit(const KnotVector& knots, double s);

}  // namespace rope
