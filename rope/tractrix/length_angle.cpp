// SPDX-License-Identifier: MIT
#include "rope/tractrix/length_angle.h"

#include <cmath>
#include <string>

#include "rope/common/error.h"
#include "rope/common/types.h"
#include "rope/spline/gauss_legendre.h"

namespace rope {
namespace {

const double kPi = std::acos(-1.0);

// Composite Gauss–Legendre over [0, 1]. The speed |C'(u)| is smooth for theta >= 5° (its minimum
// stays away from 0), so 16 pieces of 16 points reach ~1e-13.
constexpr int kPieces = 16;
constexpr int kPoints = 16;

// Control points of the piece for the model, with P2 at the origin and sides of length 1.
void piecePoints(LengthAngleModel model, double theta, Vec3 (&p)[4]) {
  p[0] = Vec3(1.0, 0.0, 0.0);
  p[1] = Vec3::Zero();
  p[2] = Vec3(std::cos(theta), std::sin(theta), 0.0);
  if (model == LengthAngleModel::kCubicBothAngles) {
    // [B] §2.3: P4 = P3 - L (cos(theta1 + theta2), sin(theta1 + theta2)) with theta1 = theta2.
    p[3] = p[2] - Vec3(std::cos(2.0 * theta), std::sin(2.0 * theta), 0.0);
  } else {
    p[3] = 2.0 * p[2];  // theta2 = pi: P4 continues the side P2 P3
  }
}

// Speed |C'(u)| of the uniform piece on [0, 1].
double pieceSpeed(LengthAngleModel model, const Vec3 (&p)[4], double u) {
  Vec3 velocity;
  if (model == LengthAngleModel::kQuadratic) {
    // [B] eq. 4: N1' = -(1-u), N2' = 1 - 2u, N3' = u.
    velocity = -(1.0 - u) * p[0] + (1.0 - 2.0 * u) * p[1] + u * p[2];
  } else {
    // [B] eq. 10 derivatives (docs/method.md eq. 44: the corrected N4 = u^3/6).
    const double n1 = -0.5 * (1.0 - u) * (1.0 - u);
    const double n2 = 1.5 * u * u - 2.0 * u;
    const double n3 = -1.5 * u * u + u + 0.5;
    const double n4 = 0.5 * u * u;
    velocity = n1 * p[0] + n2 * p[1] + n3 * p[2] + n4 * p[3];
  }
  return velocity.norm();
}

void requireAngle(double theta) {
  requireFinite("includedAngle", theta);
  if (theta < kMinThresholdAngle || theta > kPi) {
    throw InvalidArgument("includedAngle", formatValue(theta),
                          "must be in [" + formatValue(kMinThresholdAngle) + ", pi]");
  }
}

double shortfall(LengthAngleModel model, double theta) {
  Vec3 p[4];
  piecePoints(model, theta, p);
  const GaussRule rule = gaussLegendre(kPoints);
  const double half = 0.5 / kPieces;
  double length = 0.0;
  for (int piece = 0; piece < kPieces; ++piece) {
    const double mid = (piece + 0.5) / kPieces;
    double sum = 0.0;
    for (int g = 0; g < rule.count; ++g) sum += rule.weights[g] * pieceSpeed(model, p, mid + half * rule.nodes[g]);
    length += half * sum;
  }
  // Straight pieces with unit sides have unit length for both degrees ([B] eq. 6: l(pi) = L).
  return 1.0 - length;
}

}  // namespace

static void requireModel(LengthAngleModel model) {
  if (model != LengthAngleModel::kQuadratic && model != LengthAngleModel::kCubicOneAngle &&
      model != LengthAngleModel::kCubicBothAngles) {
    throw InvalidArgument("model", std::to_string(static_cast<int>(model)), "is not a LengthAngleModel");
  }
}

double pieceLengthShortfall(LengthAngleModel model, double includedAngle) {
  requireModel(model);
  requireAngle(includedAngle);
  return shortfall(model, includedAngle);
}

double angleForLengthShortfall(LengthAngleModel model, double target) {
  requireModel(model);
  requireFinite("shortfall", target);
  const double largest = shortfall(model, kMinThresholdAngle);
  if (!(target > 0.0 && target < largest)) {
    throw InvalidArgument("shortfall", formatValue(target),
                          "must be in (0, " + formatValue(largest) + ") for this model");
  }
  // Bisection on [5°, pi]: shortfall decreases monotonically from `largest` to 0.
  double lo = kMinThresholdAngle;
  double hi = kPi;
  for (int iteration = 0; iteration < 200 && hi - lo > 1e-15; ++iteration) {
    const double mid = 0.5 * (lo + hi);
    if (shortfall(model, mid) > target) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

AngleThresholds thresholdsForLengthError(double tolerance, double mergeFraction, LengthAngleModel model) {
  requireModel(model);
  requireFinite("mergeFraction", mergeFraction);
  if (!(mergeFraction > 0.0 && mergeFraction < 1.0)) {
    throw InvalidArgument("mergeFraction", formatValue(mergeFraction), "must be in (0, 1)");
  }
  requireFinite("tolerance", tolerance);
  const double largest = shortfall(model, kMinThresholdAngle);
  if (!(tolerance > 0.0 && tolerance < largest)) {
    throw InvalidArgument("tolerance", formatValue(tolerance),
                          "must be in (0, " + formatValue(largest) + ") for this model");
  }
  AngleThresholds thresholds;
  thresholds.subdivisionAngle = angleForLengthShortfall(model, tolerance);
  thresholds.mergingAngle = angleForLengthShortfall(model, mergeFraction * tolerance);
  if (!(thresholds.mergingAngle > thresholds.subdivisionAngle && thresholds.mergingAngle < kPi)) {
    throw InvalidArgument("tolerance", formatValue(tolerance),
                          "is too small to separate the merging angle from the subdivision angle and pi");
  }
  return thresholds;
}

}  // namespace rope
