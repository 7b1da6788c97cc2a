// SPDX-License-Identifier: MIT
#include "rope/rod/adaptivity.h"

#include <algorithm>

#include "rope/spline/control_polygon.h"
#include "rope/spline/knot_insertion.h"

namespace rope {

double grevilleAbscissa(const KnotVector& knots, int i) {
  const int d = knots.degree();
  double sum = 0.0;
  for (int k = 1; k <= d; ++k) sum += knots[i + k];
  return sum / d;
}

void bendMeasures(const PointList& points, std::vector<double>& bend) {
  const int n = static_cast<int>(points.size());
  bend.assign(points.size(), 0.0);
  for (int i = 1; i + 1 < n; ++i) bend[static_cast<size_t>(i)] = bendMeasure(points, i);
}

void curvatureInsertionSpans(const KnotVector& knots, const std::vector<double>& bend,
                             double insertThreshold, std::vector<int>& spans) {
  spans.clear();
  const int n = static_cast<int>(bend.size());
  double left = grevilleAbscissa(knots, 0);
  for (int i = 0; i + 1 < n; ++i) {
    const double right = grevilleAbscissa(knots, i + 1);
    if (bend[static_cast<size_t>(i)] > insertThreshold || bend[static_cast<size_t>(i + 1)] > insertThreshold) {
      const int k = knots.findSpanUnchecked(0.5 * (left + right));
      if (spans.empty() || spans.back() != k) spans.push_back(k);
    }
    left = right;
  }
}

LocalRemoval localRemoval(const KnotRemoval& plan, const PointList& values) {
  const int size = static_cast<int>(values.size());
  const int lo = std::max(0, plan.span - plan.degree - 2);
  const int hi = std::min(size - 1, plan.span + 3);
  KnotRemoval shifted = plan;
  shifted.span -= lo;
  LocalRemoval result;
  result.offset = lo;
  result.after.assign(values.begin() + lo, values.begin() + hi + 1);
  shifted.apply(result.after);
  // Insert the knot again into the shifted window: same span and alphas as the removal (both refer to
  // the knot vector after removal).
  KnotInsertion again;
  again.parameter = plan.parameter;
  again.span = shifted.span;
  again.degree = plan.degree;
  again.alpha = plan.alpha;
  PointList restored = result.after;
  again.apply(restored);
  double error = 0.0;
  for (size_t i = 0; i < restored.size(); ++i)
    error = std::max(error, (restored[i] - values[static_cast<size_t>(lo) + i]).norm());
  result.error = error;
  return result;
}

}  // namespace rope
