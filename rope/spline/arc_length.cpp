// SPDX-License-Identifier: MIT
#include "rope/spline/arc_length.h"

#include <algorithm>
#include <string>

#include "rope/common/error.h"
#include "rope/spline/bspline_basis.h"
#include "rope/spline/gauss_legendre.h"

namespace rope {
namespace {

void requireOptions(const ArcLengthOptions& options) {
  if (options.gaussPoints < 1 || options.gaussPoints > kMaxGaussPoints) {
    throw InvalidArgument("options.gaussPoints", std::to_string(options.gaussPoints),
                          "must be in 1.." + std::to_string(kMaxGaussPoints));
  }
  if (options.piecesPerSpan < 1) {
    throw InvalidArgument("options.piecesPerSpan", std::to_string(options.piecesPerSpan), "must be >= 1");
  }
}

void requireInRange(const KnotVector& knots, const char* name, double s) {
  if (!knots.contains(s)) {
    throw InvalidArgument(name, formatValue(s),
                          "must lie in the valid range [" + formatValue(knots.validBegin()) + ", " +
                              formatValue(knots.validEnd()) + "]");
  }
}

}  // namespace

double arcLength(const KnotVector& knots, const PointList& points, double s0, double s1,
                 const ArcLengthOptions& options) {
  requireOptions(options);
  requireInRange(knots, "s0", s0);
  requireInRange(knots, "s1", s1);
  if (s1 < s0) throw InvalidArgument("s1", formatValue(s1), "must be >= s0 = " + formatValue(s0));
  if (static_cast<int>(points.size()) != knots.controlPointCount()) {
    throw InvalidArgument("points.size()", std::to_string(points.size()),
                          "must equal the knot vector's control point count " +
                              std::to_string(knots.controlPointCount()));
  }
  if (s1 == s0) return 0.0;
  const GaussRule rule = gaussLegendre(options.gaussPoints);
  const int firstSpan = knots.findSpanUnchecked(s0);
  const int lastSpan = knots.findSpanUnchecked(s1);
  BasisValues basis;
  double total = 0.0;
  for (int span = firstSpan; span <= lastSpan; ++span) {
    const double a = std::max(s0, knots[span]);
    const double b = std::min(s1, knots[span + 1]);
    if (!(b > a)) continue;  // empty (repeated knot) or outside [s0, s1]
    // |C'| is smooth inside a span, so Gauss–Legendre converges fast on each piece.
    const double pieceLength = (b - a) / options.piecesPerSpan;
    for (int piece = 0; piece < options.piecesPerSpan; ++piece) {
      const double lo = a + piece * pieceLength;
      const double half = 0.5 * pieceLength;
      const double mid = lo + half;
      double sum = 0.0;
      for (int g = 0; g < rule.count; ++g) {
        const double s = mid + half * rule.nodes[g];
        evaluateBasis(knots, span, s, 1, basis);
        Vec3 velocity = Vec3::Zero();
        const int first = basis.firstIndex();
        for (int j = 0; j <= basis.degree; ++j) {
          velocity += basis.d[1][static_cast<size_t>(j)] * points[static_cast<size_t>(first + j)];
        }
        sum += rule.weights[g] * velocity.norm();
      }
      total += half * sum;
    }
  }
  return total;
}

double arcLength(const BSplineCurve& curve, const ArcLengthOptions& options) {
  return arcLength(curve.knots(), curve.controlPoints(), curve.beginParameter(), curve.endParameter(), options);
}

}  // namespace rope
