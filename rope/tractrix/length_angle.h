// SPDX-License-Identifier: MIT
#pragma once
// How much shorter a B-spline piece gets as the control polygon bends ([B] §2.2–2.3; docs/method.md §14), and
// the inverse: which angle thresholds keep that shortfall within a tolerance ([B] §3.1–3.2).
//
// All relations use equal sides (L = 1, the result is relative so L cancels) and uniform knots, and
// give the relative shortfall (l_straight - l(theta)) / l_straight of the curve piece, where theta is
// the included angle at a control point (pi = straight). They are monotone: the shortfall grows as
// theta closes. Angles in radians.

namespace rope {

enum class LengthAngleModel {
  kQuadratic,        // quadratic piece over P1 P2 P3, angle at P2 ([B] eq. 5–6)
  kCubicOneAngle,    // cubic piece over P1..P4, angle at P2, angle at P3 straight ([B] eq. 9–11)
  kCubicBothAngles,  // cubic piece over P1..P4, both angles equal (planar, turning the same way)
};

// Every function below throws InvalidArgument("model", ...) for a value outside LengthAngleModel.

// Smallest angle the threshold helper accepts: below it a "threshold" no longer describes a rope.
constexpr double kMinThresholdAngle = 0.08726646259971647;  // 5 degrees

// Relative shortfall of one piece at the included angle theta in [kMinThresholdAngle, pi]
// ("includedAngle" in errors). Numerical quadrature accurate to ~1e-12.
double pieceLengthShortfall(LengthAngleModel model, double includedAngle);

// Inverse of pieceLengthShortfall: the included angle whose shortfall equals `shortfall`, found by
// bisection on the monotone relation. Throws InvalidArgument("shortfall", ...) unless
// 0 < shortfall < pieceLengthShortfall(model, kMinThresholdAngle).
double angleForLengthShortfall(LengthAngleModel model, double shortfall);

struct AngleThresholds {
  double subdivisionAngle = 0.0;  // radians: subdivide corners whose included angle is below this
  double mergingAngle = 0.0;      // radians: merge where every affected angle is above this
};

// Thresholds for a tolerated relative length shortfall per piece ([B] §3: "the plot ... can be used
// to choose the threshold angle"). The subdivision angle is the angle at which one piece loses
// `tolerance`; the merging angle is the angle at which it loses mergeFraction * tolerance, so
// merging happens only where the curve is much straighter than the subdivision limit (hysteresis:
// a merge does not immediately provoke a subdivision). With the defaults, tolerance 0.0279 gives
// [B]'s 140°/160°.
// Throws InvalidArgument: "tolerance" outside the range of angleForLengthShortfall, "mergeFraction"
// not in (0, 1), or so small that the merging angle is no longer below pi.
AngleThresholds thresholdsForLengthError(double tolerance, double mergeFraction = 0.25,
                                         LengthAngleModel model = LengthAngleModel::kCubicOneAngle);

}  // namespace rope
