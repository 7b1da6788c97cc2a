// SPDX-License-Identifier: MIT
#include "rope/spline/curve_split.h"

#include <algorithm>
#include <string>
#include <utility>

#include "rope/common/error.h"

namespace rope {

CurveSplitPlan planCurveSplit(const KnotVector& knots, double s) {
  requireFinite("s", s);
  if (!(s > knots.validBegin() && s < knots.validEnd())) {
    throw InvalidArgument("s", formatValue(s),
                          "must lie strictly inside the valid range (" + formatValue(knots.validBegin()) + ", " +
                              formatValue(knots.validEnd()) + "); splitting at an end leaves an empty piece");
  }
  const int d = knots.degree();
  std::vector<KnotInsertion> insertions;
  // [A] §5.1: raise the multiplicity of s to d+1 by exact insertions, planned one after the other.
  KnotVector working = knots;
  for (int m = working.multiplicity(s); m < d + 1; ++m) {
    insertions.push_back(planKnotInsertion(working, s));
    working.insertValue(s);
  }
  const std::vector<double>& t = working.values();
  // r: first occurrence of s. Basis functions b_0 .. b_{r-1} live left of s, b_r .. right of it.
  const int r = static_cast<int>(std::lower_bound(t.begin(), t.end(), s) - t.begin());
  // KnotVector has no empty state, so the plan is built in one piece.
  return CurveSplitPlan{s, std::move(insertions), KnotVector(d, std::vector<double>(t.begin(), t.begin() + r + d + 1)),
                        KnotVector(d, std::vector<double>(t.begin() + r, t.end())), r};
}

}  // namespace rope
