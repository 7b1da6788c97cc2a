// SPDX-License-Identifier: MIT
#include "rope/spline/knot_insertion.h"

#include <cmath>
#include <string>

#include "rope/common/error.h"
#include "rope/spline/point_validation.h"

namespace rope {

KnotInsertion planKnotInsertion(const KnotVector& knots, double s) {
  requireFinite("s", s);
  if (!(s > knots.validBegin() && s < knots.validEnd())) {
    throw InvalidArgument("s", formatValue(s),
                          "must lie strictly inside the valid range (" + formatValue(knots.validBegin()) +
                              ", " + formatValue(knots.validEnd()) + ")");
  }
  const int d = knots.degree();
  const int span = knots.findSpanUnchecked(s);
  // Knots equal to s are s_{span}, s_{span-1}, ... (s_{span+1} > s since s < validEnd).
  int multiplicity = 0;
  while (multiplicity <= d && knots[span - multiplicity] == s) ++multiplicity;
  if (multiplicity >= d + 1) {
    throw InvalidArgument("s", formatValue(s),
                          "already has multiplicity degree+1 = " + std::to_string(d + 1) +
                              " (the curve is already cut there)");
  }
  KnotInsertion plan;
  plan.parameter = s;
  plan.span = span;
  plan.degree = d;
  // [A] eq. 3: a_i = (s* - s_i) / (s_{i+d} - s_i); s_{i+d} >= s_{span+1} > s* >= s_i, so the
  // denominator is positive and a_i in [0, 1).
  for (int j = 0; j < d; ++j) {
    const int i = span - d + 1 + j;
    plan.alpha[static_cast<size_t>(j)] = (s - knots[i]) / (knots[i + d] - knots[i]);
  }
  return plan;
}

KnotInsertion insertKnot(KnotVector& knots, PointList& points, double s) {
  if (static_cast<int>(points.size()) != knots.controlPointCount()) {
    throw InvalidArgument("points.size()", std::to_string(points.size()),
                          "must equal the knot vector's control point count " +
                              std::to_string(knots.controlPointCount()));
  }
  const KnotInsertion plan = planKnotInsertion(knots, s);
  // The map reads q_{k-d} .. q_k; an infinite one times a zero weight would make NaN.
  requireFinitePoints("points", points, static_cast<std::size_t>(plan.span - plan.degree),
                      static_cast<std::size_t>(plan.span));
  knots.insertValue(s);
  plan.apply(points);
  return plan;
}

}  // namespace rope
