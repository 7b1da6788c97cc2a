// SPDX-License-Identifier: MIT
#include "bullet_bridge/detail/rest_arc.h"

#include <cstddef>

namespace rope::bullet {

void buildRestArc(const Rod& rod, std::vector<double>& starts) {
  const RodIntegrals& integrals = rod.integrals();
  starts.resize(static_cast<std::size_t>(integrals.spanCount()) + 1);
  starts[0] = 0.0;
  for (int j = 0; j < integrals.spanCount(); ++j) {
    starts[static_cast<std::size_t>(j) + 1] = starts[static_cast<std::size_t>(j)] + integrals.span(j).restLength;
  }
}

double restArcAt(const Rod& rod, const std::vector<double>& starts, double s) {
  const KnotVector& knots = rod.knots();
  const int k = knots.findSpan(s);
  const int j = k - knots.degree();
  const double width = knots[k + 1] - knots[k];
  const double fraction = width > 0.0 ? (s - knots[k]) / width : 0.0;
  return starts[static_cast<std::size_t>(j)] +
         fraction * (starts[static_cast<std::size_t>(j) + 1] - starts[static_cast<std::size_t>(j)]);
}

}  // namespace rope::bullet
