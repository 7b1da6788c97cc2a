// SPDX-License-Identifier: MIT
#include "rope/rod/axial_force.h"

#include <cmath>

#include "rope/common/error.h"
#include "rope/spline/gauss_legendre.h"

namespace rope {

namespace {

struct Sample {
  double s = 0.0;        // parameter of the stretching point
  double tension = 0.0;  // N
};

// The stretching points of span j in parameter order, appended to out (at most kMaxSamples in all).
constexpr int kSpansAround = 2;   // spans on each side of s's span that may hold the bracketing points
constexpr int kMaxSamples = 64;

void appendSpanSamples(const Rod& rod, int j, Sample* out, int& count) {
  const RodIntegrals& integrals = rod.integrals();
  const SpanView span = integrals.span(j);
  if (span.gaussCount == 0) return;  // an empty span (repeated knot) has no points
  const KnotVector& knots = rod.knots();
  const int k = j + knots.degree();
  const double half = 0.5 * (knots[k + 1] - knots[k]), mid = 0.5 * (knots[k] + knots[k + 1]);
  const GaussRule rule = gaussLegendre(span.gaussCount);
  const double ea = rod.settings().axialStiffness();
  for (int g = 0; g < span.gaussCount && count < kMaxSamples; ++g) {
    Vec3 derivative = Vec3::Zero();
    for (int a = 0; a < span.localCount; ++a) {
      derivative += span.dBasis[g * span.localCount + a] * rod.controlPoints()[static_cast<std::size_t>(j + a)];
    }
    // l0'(s_g) from the stored weights: w0 = w J l0', w1 = w J / l0'.
    const double restMetric = std::sqrt(span.w0[g] / span.w1[g]);
    const double stretch = derivative.norm() / restMetric;
    // Method eq. 13: T = dW/dγ of W = (EA/8)(γ² − 1)² per metre of rest length.
    out[count++] = {mid + half * rule.nodes[g], 0.5 * ea * (stretch * stretch - 1.0) * stretch};
  }
}

double line(const Sample& a, const Sample& b, double s) {
  return b.s > a.s ? a.tension + (b.tension - a.tension) * (s - a.s) / (b.s - a.s) : 0.5 * (a.tension + b.tension);
}

}  // namespace

double axialForce(const Rod& rod, double s) {
  // isfinite first: an ordered comparison with NaN raises FE_INVALID (the tests trap it).
  if (!std::isfinite(s) || s < rod.beginParameter() || s > rod.endParameter()) {
    throw InvalidArgument("s", formatValue(s),
                          "must be in [" + formatValue(rod.beginParameter()) + ", " + formatValue(rod.endParameter()) + "]");
  }
  const KnotVector& knots = rod.knots();
  const int j = knots.findSpan(s) - knots.degree();
  const int spans = rod.integrals().spanCount();
  Sample samples[kMaxSamples];
  int count = 0;
  for (int i = std::max(0, j - kSpansAround); i <= std::min(spans - 1, j + kSpansAround); ++i) {
    appendSpanSamples(rod, i, samples, count);
  }
  if (count == 0) return 0.0;  // only empty spans around s: cannot happen on a valid rod
  if (count == 1) return samples[0].tension;
  // The bracketing pair, or the two nearest at either end (linear extrapolation).
  int upper = 0;
  while (upper < count && samples[upper].s < s) ++upper;
  if (upper == 0) return line(samples[0], samples[1], s);
  if (upper == count) return line(samples[count - 2], samples[count - 1], s);
  return line(samples[upper - 1], samples[upper], s);
}

}  // namespace rope
