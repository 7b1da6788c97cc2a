// SPDX-License-Identifier: MIT
#include "rope/tractrix/tractrix_segment.h"

#include <cmath>

#include "rope/common/error.h"

namespace rope {
namespace {

// Displacements below this are rescaled before normalising so that squaring cannot underflow.
constexpr double kTinyDisplacement = 1e-140;

void requireFinitePoint(const char* name, const Vec3& p) {
  for (int c = 0; c < 3; ++c) requireTractrixCoordinate(std::string(name) + "[" + std::to_string(c) + "]", p[c]);
}

}  // namespace

void requireTractrixCoordinate(const std::string& parameter, double value) {
  requireFinite(parameter, value);
  if (std::fabs(value) > kMaxTractrixCoordinate) {
    throw InvalidArgument(parameter, formatValue(value), "must be within +-1e100 (metres)");
  }
}

Vec3 tractrixMoveTrailing(const Vec3& leading, const Vec3& trailing, const Vec3& newLeading, double length) {
  const Vec3 delta = newLeading - leading;
  double q = delta.norm();
  if (q == 0.0) return trailing;  // docs/method.md §13: q = 0 moves nothing
  Vec3 u;
  if (q < kTinyDisplacement) {
    const Vec3 scaled = delta * 1e200;
    u = scaled / scaled.norm();
  } else {
    u = delta / q;
  }
  const Vec3 toLeading = leading - trailing;
  const Vec3 t = toLeading / toLeading.norm();
  const double c = t.dot(u);  // cos alpha
  const Vec3 perpendicular = t - c * u;
  const double s = perpendicular.norm();  // sin alpha, >= 0
  // tan(alpha/2) = num/den, written in the form that does not cancel: s/(1+c) for alpha <= 90°,
  // (1-c)/s beyond. (num, den) is never (0, 0).
  double num = s;
  double den = 1.0 + c;
  if (c < 0.0) {
    num = 1.0 - c;
    den = s;
  }
  if (den == 0.0) return newLeading + length * u;  // alpha = pi exactly: the segment translates
  // [B] eq. 1 in angle form (docs/method.md eq. 38): tan(alpha'/2) = tan(alpha/2) exp(-q/L). Underflow of the
  // exponential to 0 is the correct limit (the segment has aligned with u).
  const double numNew = num * std::exp(-q / length);
  double cosNew;
  double sinNew;
  // cos = (1 - r^2)/(1 + r^2), sin = 2r/(1 + r^2) with r = tan(alpha'/2); use 1/r when r > 1 so that
  // nothing overflows or divides by zero.
  if (numNew <= den) {
    const double r = numNew / den;
    const double r2 = r * r;
    cosNew = (1.0 - r2) / (1.0 + r2);
    sinNew = 2.0 * r / (1.0 + r2);
  } else {
    const double p = den / numNew;
    const double p2 = p * p;
    cosNew = (p2 - 1.0) / (p2 + 1.0);
    sinNew = 2.0 * p / (1.0 + p2);
  }
  Vec3 direction = cosNew * u;
  if (s > 0.0) direction += sinNew * (perpendicular / s);  // w = perpendicular / s
  // Near alpha = 0 or pi, perpendicular/s is not exactly orthogonal to u (cancellation in t - c u);
  // renormalising keeps the segment length exact to rounding, which the chain's guarantee needs.
  direction /= direction.norm();
  return newLeading - length * direction;
}

Vec3 tractrixTrailingPoint(const Vec3& leading, const Vec3& trailing, const Vec3& newLeading) {
  requireFinitePoint("leading", leading);
  requireFinitePoint("trailing", trailing);
  requireFinitePoint("newLeading", newLeading);
  const double length = (leading - trailing).norm();
  if (!(length > 0.0)) {
    throw InvalidArgument("trailing", "(" + formatValue(trailing.x()) + ", " + formatValue(trailing.y()) + ", " +
                                          formatValue(trailing.z()) + ")",
                          "must differ from leading (zero-length segment)");
  }
  return tractrixMoveTrailing(leading, trailing, newLeading, length);
}

}  // namespace rope
