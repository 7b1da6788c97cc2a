// SPDX-License-Identifier: MIT
#include "bullet_bridge/contact/axis_departure.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bullet_bridge/capsule_proxies.h"

namespace rope::bullet {

void boundAxisDeparture(const Rod& rod, const CapsuleProxies& proxies, std::vector<CurvePoint>& ends,
                        std::vector<double>& deviation, double& roundoff) {
  // Inside one knot span a curve of degree <= 3 is a cubic P(t) = C(s0 + t (s1 - s0)) on the capsule,
  // and its departure from the chord, delta(t) = P(t) - P(0) - t (P(1) - P(0)), vanishes at both ends:
  // delta(t) = t (1 - t) q(t) with q linear, q(0) = P'(0) - chord, q(1) = chord - P'(1). So
  // |delta| <= max(|q(0)|, |q(1)|) / 4 everywhere on the capsule; the axis's ends may also differ from
  // C(s0), C(s1) (btScalar rounding). Higher degrees, and a derivative that jumps at a knot of
  // multiplicity >= degree, get no bound (infinity: every hit of such a capsule is evaluated).
  const KnotVector& knots = rod.knots();
  const int degree = knots.degree();
  const int count = proxies.size();
  ends.resize(static_cast<size_t>(count) + 1);
  int span = -1;  // the ends come in order: each span search starts from the last end's
  for (int i = 0; i <= count; ++i) {
    const double s = i < count ? proxies.proxy(i).s0 : proxies.proxy(i - 1).s1;
    ends[static_cast<size_t>(i)] = evaluateCurveNear(knots, rod.controlPoints(), s, span);
  }
  deviation.assign(static_cast<size_t>(count), std::numeric_limits<double>::infinity());
  double scale = 0.0;
  for (int i = 0; i < count; ++i) {
    const Capsule capsule = proxies.capsule(i);
    for (int k = 0; k < 3; ++k) {
      scale = std::max({scale, std::abs(static_cast<double>(capsule.a[k])), std::abs(static_cast<double>(capsule.b[k]))});
    }
    if (degree > 3) continue;
    const CapsuleProxy& proxy = proxies.proxy(i);
    const CurvePoint& start = ends[static_cast<size_t>(i)];
    const CurvePoint& end = ends[static_cast<size_t>(i) + 1];
    // C' at s1 as evaluated comes from the span right of a knot there: the capsule's own only if C' is
    // continuous at s1.
    if (i + 1 < count && knots.multiplicity(proxy.s1) >= degree) continue;
    const double width = proxy.s1 - proxy.s0;
    const Vec3 chord = end.position - start.position;
    const double bulge = 0.25 * std::max((width * start.firstDerivative - chord).norm(),
                                         (chord - width * end.firstDerivative).norm());
    const Vec3 a(capsule.a.x(), capsule.a.y(), capsule.a.z()), b(capsule.b.x(), capsule.b.y(), capsule.b.z());
    const double axisEnds = std::max((a - start.position).norm(), (b - end.position).norm());
    deviation[static_cast<size_t>(i)] = (bulge + axisEnds) * (1.0 + 1e-9);
  }
  // The rounding of the axes' distance (btScalar) and of the curve points (double), m.
  roundoff = 16.0 * (static_cast<double>(std::numeric_limits<btScalar>::epsilon()) + 1e-16) * (1.0 + scale);
}

}  // namespace rope::bullet
