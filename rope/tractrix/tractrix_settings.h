// SPDX-License-Identifier: MIT
#pragma once
// What a user configures for a tractrix rope ([B] §3.3–4). Plain data; validateTractrixSettings()
// checks it. Angles are radians in the struct; use degrees() / setThresholdsDegrees() to work in
// degrees like [B].

#include "rope/common/types.h"

namespace rope {

// [B] §4's three algorithms.
enum class TractrixVariant {
  kPolyline,                // TRX: exact polyline of segmentCount rigid segments (lengths kept exactly)
  kSplineSubdivide,         // TRX_SD: tractrix on a B-spline control polygon, subdivision below subdivisionAngle
  kSplineSubdivideMerge,    // TRX_SD_MRG: as TRX_SD, plus merging above mergingAngle
};

// What keeps the curve's length (length_correction.h). Beyond [B].
enum class TractrixLengthCorrection {
  kNone,                // [B] as published: the tractrix keeps the polygon's sides, the curve's length drifts
  kRestoreCurveLength,  // after every step the polygon is re-laid so that the curve keeps its initial length
};

constexpr double kTractrixPi = 3.14159265358979323846;
constexpr double degrees(double value) { return value * (kTractrixPi / 180.0); }  // degrees -> radians
constexpr double toDegrees(double radians) { return radians * (180.0 / kTractrixPi); }

struct TractrixSettings {
  TractrixVariant variant = TractrixVariant::kSplineSubdivideMerge;

  // Initial number of sides: rigid segments for kPolyline (>= 1), control polygon sides for the
  // spline variants (>= degree; the control point count is segmentCount + 1). [B] §4 uses 6.
  int segmentCount = 6;

  // Spline degree for the spline variants, 2..kMaxDegree ([B] uses cubic). kPolyline ignores it.
  int degree = 3;

  // Included-angle thresholds in radians, 0 < subdivisionAngle < mergingAngle < pi ([B] §4: 140°,
  // 160°). A corner whose included angle is below subdivisionAngle is cut by knot insertion; a knot
  // is removed when every corner it affects is above mergingAngle. thresholdsForLengthError()
  // (length_angle.h) derives both from a length tolerance. kSplineSubdivide ignores mergingAngle
  // but it is validated all the same.
  double subdivisionAngle = degrees(140.0);
  double mergingAngle = degrees(160.0);

  // Bounds on the control point count for the spline variants: merging never goes below
  // minControlPoints, subdivision never above maxControlPoints; the initial count segmentCount + 1
  // must lie in between. minControlPoints = 0 means the initial count, so that merging removes only
  // what subdivision added ([B] §3.2 motivates merging that way); otherwise it must be >= degree + 1.
  // Merging below the initial resolution makes later bends cost more length (coarser polygon).
  // kPolyline ignores both.
  int minControlPoints = 0;
  int maxControlPoints = 256;

  // A merge is accepted only if it leaves no affected corner below subdivisionAngle, so that a
  // merge does not itself create a corner the next check would cut again (insert/remove flicker).
  // Off = [B]'s plain rule.
  bool guardMerges = true;

  // A merge may move the curve by at most this fraction of the initial curve length (the removal's
  // shape error, which bounds the displacement). Keeps the motion visibly continuous; [B] looks at
  // the length error only. Finite, > 0; 1e300 effectively switches it off.
  double maxMergeShapeError = 0.01;

  // kRestoreCurveLength (the default) re-lays the control polygon after every step so that the curve's
  // length stays the initial length (to 1e-12 relative in the quadrature below); kNone is [B]'s
  // TRX_SD / TRX_SD_MRG as published, whose curve loses length on tight bends. kPolyline ignores it
  // (its polyline keeps its length exactly).
  TractrixLengthCorrection lengthCorrection = TractrixLengthCorrection::kRestoreCurveLength;

  // Gauss–Legendre points per knot span for the per-step curve length (1..kMaxGaussPoints). The
  // integrand is smooth on a span; 8 points give ~1e-9 relative on the shapes a rope takes.
  int lengthGaussPoints = 8;

  // The floor minControlPoints stands for (resolves the 0 default).
  int effectiveMinControlPoints() const { return minControlPoints == 0 ? segmentCount + 1 : minControlPoints; }

  // Convenience: set both thresholds from degrees.
  void setThresholdsDegrees(double subdivisionDegrees, double mergingDegrees) {
    subdivisionAngle = degrees(subdivisionDegrees);
    mergingAngle = degrees(mergingDegrees);
  }
};

// Throws InvalidArgument naming "settings.<field>" and the value for anything out of range.
void validateTractrixSettings(const TractrixSettings& settings);

}  // namespace rope
