// SPDX-License-Identifier: MIT
#include "rope/spline/knot_removal.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "rope/common/error.h"
#include "rope/common/fixed_vector.h"
#include "rope/spline/arc_length.h"
#include "rope/spline/bspline_basis.h"
#include "rope/spline/gauss_legendre.h"
#include "rope/spline/knot_insertion.h"
#include "rope/spline/point_validation.h"

namespace rope {
namespace {

// The few control points a plan works on (d + 2: the window q_{k-d} .. q_{k+1}), in place.
using Window = FixedVector<Vec3, kMaxDegree + 2>;

// |L_new - L_old| over [a, b] where the new curve on the same knots has control points
// points + delta on indices lo .. lo + delta.size() - 1 (the candidate with the knot re-inserted).
// Both integrands use the same nodes, so spans where delta's functions vanish cancel exactly.
double lengthChange(const KnotVector& knots, const PointList& points, int lo, const Window& delta,
                    double a, double b) {
  const ArcLengthOptions options;
  const GaussRule rule = gaussLegendre(options.gaussPoints);
  const int firstSpan = knots.findSpanUnchecked(a);
  const int lastSpan = knots.findSpanUnchecked(b);
  const int hi = lo + static_cast<int>(delta.size()) - 1;
  BasisValues basis;
  double oldLength = 0.0;
  double newLength = 0.0;
  for (int span = firstSpan; span <= lastSpan; ++span) {
    const double s0 = std::max(a, knots[span]);
    const double s1 = std::min(b, knots[span + 1]);
    if (!(s1 > s0)) continue;
    const double pieceLength = (s1 - s0) / options.piecesPerSpan;
    const double half = 0.5 * pieceLength;
    for (int piece = 0; piece < options.piecesPerSpan; ++piece) {
      const double mid = s0 + piece * pieceLength + half;
      double oldSum = 0.0;
      double newSum = 0.0;
      for (int g = 0; g < rule.count; ++g) {
        const double s = mid + half * rule.nodes[g];
        evaluateBasis(knots, span, s, 1, basis);
        Vec3 velocity = Vec3::Zero();
        Vec3 change = Vec3::Zero();
        const int first = basis.firstIndex();
        for (int j = 0; j <= basis.degree; ++j) {
          const int i = first + j;
          const double db = basis.d[1][static_cast<size_t>(j)];
          velocity += db * points[static_cast<size_t>(i)];
          if (i >= lo && i <= hi) change += db * delta[static_cast<size_t>(i - lo)];
        }
        oldSum += rule.weights[g] * velocity.norm();
        newSum += rule.weights[g] * (velocity + change).norm();
      }
      oldLength += half * oldSum;
      newLength += half * newSum;
    }
  }
  return std::fabs(newLength - oldLength);
}

}  // namespace

namespace {

KnotRemoval planRemoval(const KnotVector& knots, const PointList& points, double s, bool withLength) {
  requireFinite("s", s);
  if (!(s > knots.validBegin() && s < knots.validEnd())) {
    throw InvalidArgument("s", formatValue(s),
                          "must be a knot strictly inside the valid range (" + formatValue(knots.validBegin()) +
                              ", " + formatValue(knots.validEnd()) + ")");
  }
  const int multiplicity = knots.multiplicity(s);
  if (multiplicity == 0) throw InvalidArgument("s", formatValue(s), "is not a knot");
  const int d = knots.degree();
  const int n = knots.controlPointCount();
  if (static_cast<int>(points.size()) != n) {
    throw InvalidArgument("points.size()", std::to_string(points.size()),
                          "must equal the knot vector's control point count " + std::to_string(n));
  }
  if (n - 1 < d + 1) {
    throw InvalidArgument("points.size()", std::to_string(points.size()),
                          "removal would leave fewer than degree+1 = " + std::to_string(d + 1) +
                              " control points");
  }
  const std::vector<double>& t = knots.values();
  // The last occurrence; s is strictly inside the valid range, so d < r < n.
  const int r = static_cast<int>(std::upper_bound(t.begin(), t.end(), s) - t.begin()) - 1;
  const int k = r - 1;  // span of s in the knot vector after removal

  KnotRemoval removal;
  removal.parameter = s;
  removal.knotIndex = r;
  removal.span = k;
  removal.degree = d;
  removal.multiplicityAfter = multiplicity - 1;
  // a_i on the knot vector T' after removal: T'_i = T_i for i < r and T'_i = T_{i+1} for i >= r.
  for (int j = 0; j < d; ++j) {
    const int i = k - d + 1 + j;
    removal.alpha[static_cast<size_t>(j)] = (s - t[static_cast<size_t>(i)]) /
                                            (t[static_cast<size_t>(i + d + 1)] - t[static_cast<size_t>(i)]);
  }

  // Work on the window q_{k-d} .. q_{k+1}, the only points the sweeps read or write.
  const int lo = k - d;
  // Every point the sweeps and the length integrals read must be finite (the traps catch NaN).
  requireFinitePoints("points", points, static_cast<std::size_t>(std::max(0, lo - d)),
                     static_cast<std::size_t>(std::min(n - 1, k + d + 1)));
  Window window;
  window.assign(points.begin() + lo, points.begin() + k + 2);
  KnotRemoval local = removal;
  local.span = d;
  KnotInsertion reinsertion;
  reinsertion.parameter = s;
  reinsertion.span = d;
  reinsertion.degree = d;
  reinsertion.alpha = removal.alpha;

  // The curve changes only where the window's basis functions live: [T_{k-d}, T_{k+d+2}].
  const double a = std::max(knots.validBegin(), t[static_cast<size_t>(lo)]);
  const double b = std::min(knots.validEnd(), t[static_cast<size_t>(k + d + 2)]);
  for (int side = 0; side < 2; ++side) {
    Window candidate = window;
    local.apply(candidate, static_cast<KnotRemoval::Side>(side));
    reinsertion.apply(candidate);
    Window delta;
    delta.resize(window.size());
    double shape = 0.0;
    for (size_t i = 0; i < window.size(); ++i) {
      delta[i] = candidate[i] - window[i];
      shape = std::max(shape, delta[i].norm());
    }
    if (!std::isfinite(shape)) throw NumericalFailure("knot removal at s = " + formatValue(s) + " overflowed");
    removal.shapeError[static_cast<size_t>(side)] = shape;
    if (withLength) removal.lengthError[static_cast<size_t>(side)] = lengthChange(knots, points, lo, delta, a, b);
  }
  if (!withLength) return removal;
  // [B] §3.2: keep the candidate with the smaller length error; ties go to the left sweep.
  removal.chosen = removal.lengthError[1] < removal.lengthError[0] ? KnotRemoval::kFromRight : KnotRemoval::kFromLeft;
  return removal;
}

}  // namespace

KnotRemoval planKnotRemoval(const KnotVector& knots, const PointList& points, double s) {
  return planRemoval(knots, points, s, true);
}

KnotRemoval planKnotRemovalShape(const KnotVector& knots, const PointList& points, double s) {
  return planRemoval(knots, points, s, false);
}

KnotRemoval removeKnot(KnotVector& knots, PointList& points, double s) {
  const KnotRemoval removal = planKnotRemoval(knots, points, s);
  knots.eraseAt(removal.knotIndex);
  removal.apply(points);
  return removal;
}

}  // namespace rope
