// SPDX-License-Identifier: MIT
#pragma once
// Arc length of a B-spline curve, integral of |C'(s)| ds, by Gauss–Legendre quadrature on each knot
// span (the integrand is smooth inside a span, so the rule converges fast there). Metres.

#include "rope/common/types.h"
#include "rope/spline/bspline_curve.h"
#include "rope/spline/knot_vector.h"

namespace rope {

struct ArcLengthOptions {
  int gaussPoints = 16;       // per piece, 1..kMaxGaussPoints
  int piecesPerSpan = 4;      // each knot span is cut into this many equal pieces (>= 1)
};

// Length over [s0, s1] (s0 <= s1, both inside the valid range; "s0"/"s1" in errors).
double arcLength(const KnotVector& knots, const PointList& points, double s0, double s1,
                 const ArcLengthOptions& options = {});
// Length over the whole valid range.
double arcLength(const BSplineCurve& curve, const ArcLengthOptions& options = {});

}  // namespace rope
