// SPDX-License-Identifier: MIT
#include "rope/tractrix/tractrix_settings.h"

#include <string>

#include "rope/common/error.h"
#include "rope/spline/gauss_legendre.h"
#include "rope/spline/knot_vector.h"

namespace rope {
namespace {

void requireInt(const char* name, int value, int lo, int hi, const std::string& expected) {
  if (value < lo || value > hi) throw InvalidArgument(name, std::to_string(value), expected);
}

}  // namespace

void validateTractrixSettings(const TractrixSettings& settings) {
  const TractrixVariant variant = settings.variant;
  if (variant != TractrixVariant::kPolyline && variant != TractrixVariant::kSplineSubdivide &&
      variant != TractrixVariant::kSplineSubdivideMerge) {
    throw InvalidArgument("settings.variant", std::to_string(static_cast<int>(variant)), "is not a TractrixVariant");
  }
  if (settings.lengthCorrection != TractrixLengthCorrection::kNone &&
      settings.lengthCorrection != TractrixLengthCorrection::kRestoreCurveLength) {
    throw InvalidArgument("settings.lengthCorrection", std::to_string(static_cast<int>(settings.lengthCorrection)),
                          "is not a TractrixLengthCorrection");
  }
  // Finiteness before any ordered comparison (NaN comparisons raise FE_INVALID).
  requireFinite("settings.subdivisionAngle", settings.subdivisionAngle);
  requireFinite("settings.mergingAngle", settings.mergingAngle);
  if (!(settings.subdivisionAngle > 0.0)) {
    throw InvalidArgument("settings.subdivisionAngle", formatValue(settings.subdivisionAngle), "must be > 0");
  }
  if (!(settings.mergingAngle > settings.subdivisionAngle)) {
    throw InvalidArgument("settings.mergingAngle", formatValue(settings.mergingAngle),
                          "must be > settings.subdivisionAngle = " + formatValue(settings.subdivisionAngle));
  }
  if (!(settings.mergingAngle < kTractrixPi)) {
    throw InvalidArgument("settings.mergingAngle", formatValue(settings.mergingAngle), "must be < pi (radians)");
  }
  requirePositive("settings.maxMergeShapeError", settings.maxMergeShapeError);
  requireInt("settings.lengthGaussPoints", settings.lengthGaussPoints, 1, kMaxGaussPoints,
             "must be in 1.." + std::to_string(kMaxGaussPoints));
  constexpr int kLargest = 1 << 24;  // keeps counts and their sums far from int overflow
  if (variant == TractrixVariant::kPolyline) {
    requireInt("settings.segmentCount", settings.segmentCount, 1, kLargest, "must be in 1..2^24");
    return;
  }
  requireInt("settings.degree", settings.degree, 2, kMaxDegree,
             "must be in 2.." + std::to_string(kMaxDegree) + " for the spline variants");
  requireInt("settings.segmentCount", settings.segmentCount, settings.degree, kLargest,
             "must be in degree.." + std::to_string(kLargest) + " for the spline variants");
  if (settings.minControlPoints != 0) {
    requireInt("settings.minControlPoints", settings.minControlPoints, settings.degree + 1, settings.segmentCount + 1,
               "must be 0 (the initial count) or in degree+1..segmentCount+1 = " +
                   std::to_string(settings.degree + 1) + ".." + std::to_string(settings.segmentCount + 1));
  }
  requireInt("settings.maxControlPoints", settings.maxControlPoints, settings.segmentCount + 1, kLargest,
             "must be in segmentCount+1..2^24 = " + std::to_string(settings.segmentCount + 1) + "..2^24");
}

}  // namespace rope
