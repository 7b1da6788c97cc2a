// SPDX-License-Identifier: MIT
// Rod: paying out and reeling in at an end (a winch; docs/method.md §16). The end knots move and the
// end span's polynomial is re-expressed on them through its blossom (eq. 50), for positions,
// velocities and the rest curve alike: every other span keeps its polynomial, so the remaining rope
// does not move and its material (rest metric, mass, stiffness) is untouched. Knots enter by exact
// insertion (§2) and leave by removal (§3) so the end span stays between minKnotSpacing and twice
// the rope's nominal spacing.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "rope/common/error.h"
#include "rope/rod/rod.h"
#include "rope/spline/gauss_legendre.h"

namespace rope {

namespace {

// Blossom f(u_1, ..., u_d) of the polynomial of the first span (k = d) of the curve with knots t and
// control points p: de Boor's algorithm with the parameter u_r at level r (method eq. 50). Valid for
// any u, inside the span or not (extrapolation of the same polynomial).
Vec3 firstSpanBlossom(const std::vector<double>& t, const PointList& p, int d, const double* u) {
  Vec3 work[kMaxDegree + 1];
  for (int a = 0; a <= d; ++a) work[a] = p[static_cast<std::size_t>(a)];
  for (int r = 1; r <= d; ++r) {
    for (int i = d; i >= r; --i) {
      const double ti = t[static_cast<std::size_t>(i)];
      const double alpha = (u[r - 1] - ti) / (t[static_cast<std::size_t>(i + d + 1 - r)] - ti);
      work[i] = (1.0 - alpha) * work[i - 1] + alpha * work[i];
    }
  }
  return work[d];
}

// Derivative of the first span's polynomial at s. The blossom is affine in each argument, so
// f(s, ..., s, s + delta) - f(s, ..., s) = delta f'(s) / d exactly.
Vec3 firstSpanDerivative(const std::vector<double>& t, const PointList& p, int d, double s) {
  double u[kMaxDegree];
  std::fill(u, u + d, s);
  const Vec3 at = firstSpanBlossom(t, p, d, u);
  const double delta = t[static_cast<std::size_t>(d + 1)] - t[static_cast<std::size_t>(d)];
  u[d - 1] = s + delta;
  return (static_cast<double>(d) / delta) * (firstSpanBlossom(t, p, d, u) - at);
}

// Rest arc length of the first span's polynomial from x to a (negative for x > a), m.
double firstSpanLength(const std::vector<double>& t, const PointList& rest, int d, double x, double a) {
  const GaussRule rule = gaussLegendre(8);
  const double half = 0.5 * (a - x);
  double sum = 0.0;
  for (int g = 0; g < rule.count; ++g) {
    const double s = 0.5 * (a + x) + half * rule.nodes[g];
    sum += rule.weights[g] * firstSpanDerivative(t, rest, d, s).norm();
  }
  return half * sum;
}

// The knots and fields seen from the other end: s -> -s (exact in floating point), so one routine
// moves either end.
void mirror(std::vector<double>& knots, PointList* const* fields, int fieldCount) {
  std::reverse(knots.begin(), knots.end());
  for (double& k : knots) k = -k;
  for (int f = 0; f < fieldCount; ++f) std::reverse(fields[f]->begin(), fields[f]->end());
}

}  // namespace

double Rod::endSpanRestLength(End end) const {
  return integrals_.span(end == End::kBegin ? 0 : integrals_.spanCount() - 1).restLength;
}

void Rod::moveEnd(End end, double length) {
  const int d = degree();
  const double oldEnd = end == End::kBegin ? beginParameter() : endParameter();
  std::vector<double> t = knots_.values();
  PointList* fields[3] = {&points_, &velocities_, &rest_};
  if (end == End::kEnd) mirror(t, fields, 3);
  // New begin x with rest length `length` between x and the old begin a (eq. 51), by Newton on the
  // rest polynomial (one step is exact for a rest curve parametrised by arc length).
  const double a = t[static_cast<std::size_t>(d)];
  double x = a - length / firstSpanDerivative(t, rest_, d, a).norm();
  for (int iteration = 0; iteration < 30; ++iteration) {
    const double step = (firstSpanLength(t, rest_, d, x, a) - length) / firstSpanDerivative(t, rest_, d, x).norm();
    x += step;
    if (!(std::abs(step) > 1e-15 * (std::abs(x) + std::abs(length)))) break;
  }
  // Control point i is the blossom at its knots t_{i+1} .. t_{i+d} (eq. 50); the first d have the
  // moved end knot among them, the rest do not change.
  for (PointList* field : fields) {
    Vec3 moved[kMaxDegree];
    for (int i = 0; i < d; ++i) {
      double u[kMaxDegree];
      for (int r = 0; r < d; ++r) u[r] = (i + 1 + r <= d) ? x : t[static_cast<std::size_t>(i + 1 + r)];
      moved[i] = firstSpanBlossom(t, *field, d, u);
    }
    for (int i = 0; i < d; ++i) (*field)[static_cast<std::size_t>(i)] = moved[i];
  }
  for (int j = 0; j <= d; ++j) t[static_cast<std::size_t>(j)] = x;
  if (end == End::kEnd) mirror(t, fields, 3);
  knots_ = KnotVector(d, std::move(t));
  integrals_.build(knots_, rest_, settings_.effectiveLinearDensity(), settings_.effectiveBendingStiffness(),
                   integrals_.gaussCount(), settings_.stretchingQuadrature);
  trialValid_ = false;
  restartHistory();  // the end span's basis changed
  // Whatever held or loaded the end moves with it (the winch's pin, its spring).
  const double newEnd = end == End::kBegin ? beginParameter() : endParameter();
  for (Pin& pin : pins_) {
    if (pin.parameter == oldEnd) pin.parameter = newEnd;
  }
  for (auto& pointMass : pointMasses_) {
    if (pointMass.first == oldEnd) pointMass.first = newEnd;
  }
  for (PointLoad& load : loads_) {
    if (load.parameter == oldEnd) load.parameter = newEnd;
  }
  for (Spring& spring : springs_) {
    if (spring.parameter == oldEnd) spring.parameter = newEnd;
  }
  for (double& marked : markedInteractions_) {
    if (marked == oldEnd) marked = newEnd;
  }
}

double Rod::reelInLimit(End end) const {
  const double at = end == End::kBegin ? beginParameter() : endParameter();
  double limit = restLength() - minimumRestLength();
  const auto keepAway = [&](double s) {
    if (s != at) limit = std::min(limit, restDistance(at, s) - settings_.minKnotSpacing);
  };
  for (const Pin& pin : pins_) keepAway(pin.parameter);
  for (const auto& pointMass : pointMasses_) keepAway(pointMass.first);
  for (const PointLoad& load : loads_) keepAway(load.parameter);
  for (const Spring& spring : springs_) keepAway(spring.parameter);
  for (const double marked : markedInteractions_) keepAway(marked);
  // Within rounding of zero (the 1e-12 of the rest length payOut accepts beyond the limit) it is zero:
  // an end reeled in to its limit reads 0, not the 1e-17 m the quadratures leave.
  return limit > 1e-12 * restLength() ? limit : 0.0;
}

void Rod::payOut(End end, double length) {
  if (end != End::kBegin && end != End::kEnd) {
    throw InvalidArgument("end", std::to_string(static_cast<int>(end)), "is not a Rod::End");
  }
  requireFinite("length", length);
  if (length < 0.0) {
    const double limit = reelInLimit(end);
    // A request at the limit itself passes: the limit is a sum of quadratures, off by rounding.
    if (-length > limit + 1e-12 * restLength()) {
      throw InvalidArgument("length", formatValue(length),
                            "reels in more than the " + formatValue(limit) +
                                " m this end allows (the rope keeps minimumRestLength() = " +
                                formatValue(minimumRestLength()) +
                                " m and settings.minKnotSpacing from every pin, clamp, point mass and queued load)");
    }
  }
  const int d = degree();
  // Nominal knot spacing: the rope's initial resolution, never finer than adaptivity splits.
  const double spacing = std::max(settings_.restLength / std::max(1, settings_.initialControlPoints - d),
                                  2.0 * settings_.minKnotSpacing);
  // Reeling in, the knot next to the end leaves once the end span would be shorter than half the
  // nominal spacing (a quarter of the span at which paying out inserts one: hysteresis). Waiting until
  // minKnotSpacing left a span 60 times shorter than its neighbour, where removing the knot moved the
  // curve by a strain comparable to the rope's own: a 10 kg box on 1.3 m of a stiff rope reeled in
  // at 0.1 m/s had its control points kicked to up to 88 m/s (docs/method.md §16).
  const double removeBelow = std::max(settings_.minKnotSpacing, 0.5 * spacing);
  double remaining = length;
  while (remaining != 0.0) {
    const double chunk = std::min(std::abs(remaining), spacing);
    if (remaining > 0.0) {
      moveEnd(end, chunk);
      if (endSpanRestLength(end) > 2.0 * spacing) {
        const int k = end == End::kBegin ? d : controlPointCount() - 1;
        insertKnotUnchecked(0.5 * (knots_[k] + knots_[k + 1]));  // exact (eq. 4)
      }
      remaining -= chunk;
    } else {
      if (endSpanRestLength(end) - chunk < removeBelow && controlPointCount() > d + 1) {
        // The neighbouring knot leaves while the end span is still half the nominal spacing (eq. 7).
        removeKnot(end == End::kBegin ? knots_[d + 1] : knots_[controlPointCount() - 1]);
        continue;
      }
      moveEnd(end, -chunk);
      remaining += chunk;
    }
  }
}

}  // namespace rope
