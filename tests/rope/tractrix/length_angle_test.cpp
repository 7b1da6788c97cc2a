// SPDX-License-Identifier: MIT
// Curve length vs included angle (docs/method.md §14 check table) and the threshold helper built on it.
#include "rope/tractrix/length_angle.h"

#include <gtest/gtest.h>

#include <cmath>

#include "rope/common/error.h"
#include "rope/tractrix/tractrix_settings.h"

namespace rope {
namespace {

struct TableRow {
  double degrees;
  double quadratic;
  double cubicOne;
  double cubicBoth;
};

// docs/method.md §14, values recomputed independently ("check").
constexpr TableRow kTable[] = {
    {60.0, 0.3099, 0.2122, 0.4316},
    {100.0, 0.1518, 0.1053, 0.2193},
    {140.0, 0.0400, 0.0279, 0.0593},
    {160.0, 0.0101, 0.0071, 0.0151},
};

TEST(LengthAngle, MatchesTheSpecCheckTable) {
  for (const TableRow& row : kTable) {
    const double theta = degrees(row.degrees);
    EXPECT_NEAR(pieceLengthShortfall(LengthAngleModel::kQuadratic, theta), row.quadratic, 5e-5) << row.degrees;
    EXPECT_NEAR(pieceLengthShortfall(LengthAngleModel::kCubicOneAngle, theta), row.cubicOne, 5e-5) << row.degrees;
    EXPECT_NEAR(pieceLengthShortfall(LengthAngleModel::kCubicBothAngles, theta), row.cubicBoth, 5e-5)
        << row.degrees;
  }
}

TEST(LengthAngle, QuadraticMatchesClosedFormEquationSix) {
  // [B] eq. 6 for L1 = L2 = 1, rewritten with c = cos(theta) (the extracted text is garbled; this is
  // the integral of eq. 5 done by hand, |C'|^2 = 2(1+c)(u - 1/2)^2 + (1-c)/2): with h = sqrt((1+c)/2),
  // l = 1/2 + (1-c)/(8h) ln((1+h)/(1-h)); l -> 1 as theta -> pi and 1/2 as theta -> 0 ([B] App. A).
  for (double deg : {20.0, 60.0, 90.0, 120.0, 150.0, 175.0}) {
    const double c = std::cos(degrees(deg));
    const double h = std::sqrt(0.5 * (1.0 + c));
    const double length = 0.5 + (1.0 - c) / (8.0 * h) * std::log((1.0 + h) / (1.0 - h));
    EXPECT_NEAR(pieceLengthShortfall(LengthAngleModel::kQuadratic, degrees(deg)), 1.0 - length, 1e-12) << deg;
  }
}

TEST(LengthAngle, StraightPiecesLoseNothingAndShortfallIsMonotone) {
  for (LengthAngleModel model :
       {LengthAngleModel::kQuadratic, LengthAngleModel::kCubicOneAngle, LengthAngleModel::kCubicBothAngles}) {
    EXPECT_NEAR(pieceLengthShortfall(model, kTractrixPi), 0.0, 1e-14);
    double previous = 1.0;
    for (int i = 0; i <= 400; ++i) {
      const double theta = kMinThresholdAngle + (kTractrixPi - kMinThresholdAngle) * i / 400.0;
      const double value = pieceLengthShortfall(model, theta);
      EXPECT_LT(value, previous) << "not decreasing at " << theta;
      previous = value;
    }
  }
}

TEST(LengthAngle, InverseRecoversTheAngle) {
  for (LengthAngleModel model :
       {LengthAngleModel::kQuadratic, LengthAngleModel::kCubicOneAngle, LengthAngleModel::kCubicBothAngles}) {
    for (double deg : {10.0, 45.0, 100.0, 140.0, 160.0, 179.0}) {
      const double shortfall = pieceLengthShortfall(model, degrees(deg));
      EXPECT_NEAR(angleForLengthShortfall(model, shortfall), degrees(deg), 1e-9) << deg;
    }
  }
}

TEST(LengthAngle, ThresholdHelperReproducesPaperDefaults) {
  // [B] §4: 140° subdivision corresponds to 2.79% per cubic piece; a quarter of it gives ~160°.
  const AngleThresholds thresholds = thresholdsForLengthError(0.0279);
  EXPECT_NEAR(toDegrees(thresholds.subdivisionAngle), 140.0, 0.05);
  EXPECT_NEAR(toDegrees(thresholds.mergingAngle), 160.0, 0.3);
  // The check table's entries invert to their angles, for each model.
  EXPECT_NEAR(toDegrees(thresholdsForLengthError(0.1053).subdivisionAngle), 100.0, 0.05);
  EXPECT_NEAR(toDegrees(thresholdsForLengthError(0.0400, 0.25, LengthAngleModel::kQuadratic).subdivisionAngle),
              140.0, 0.05);
  EXPECT_NEAR(
      toDegrees(thresholdsForLengthError(0.0151, 0.5, LengthAngleModel::kCubicBothAngles).subdivisionAngle),
      160.0, 0.05);
  // Tighter tolerance, tighter (larger) angles; the merge angle always lies between it and pi.
  double previous = 0.0;
  for (double tolerance : {0.2, 0.1, 0.05, 0.01, 1e-3, 1e-5}) {
    const AngleThresholds t = thresholdsForLengthError(tolerance);
    EXPECT_GT(t.subdivisionAngle, previous);
    EXPECT_GT(t.mergingAngle, t.subdivisionAngle);
    EXPECT_LT(t.mergingAngle, kTractrixPi);
    previous = t.subdivisionAngle;
  }
}

TEST(LengthAngle, RejectsBadInput) {
  const double nan = std::nan("");
  EXPECT_THROW(pieceLengthShortfall(LengthAngleModel::kQuadratic, nan), InvalidArgument);
  EXPECT_THROW(pieceLengthShortfall(LengthAngleModel::kQuadratic, 0.0), InvalidArgument);
  EXPECT_THROW(pieceLengthShortfall(LengthAngleModel::kQuadratic, 3.5), InvalidArgument);
  EXPECT_THROW(angleForLengthShortfall(LengthAngleModel::kCubicOneAngle, 0.0), InvalidArgument);
  EXPECT_THROW(angleForLengthShortfall(LengthAngleModel::kCubicOneAngle, 0.5), InvalidArgument);
  EXPECT_THROW(angleForLengthShortfall(LengthAngleModel::kCubicOneAngle, nan), InvalidArgument);
  EXPECT_THROW(thresholdsForLengthError(-0.01), InvalidArgument);
  EXPECT_THROW(thresholdsForLengthError(nan), InvalidArgument);
  EXPECT_THROW(thresholdsForLengthError(0.9), InvalidArgument);
  EXPECT_THROW(thresholdsForLengthError(0.03, 0.0), InvalidArgument);
  EXPECT_THROW(thresholdsForLengthError(0.03, 1.0), InvalidArgument);
  EXPECT_THROW(thresholdsForLengthError(0.03, nan), InvalidArgument);
  EXPECT_THROW(thresholdsForLengthError(1e-300), InvalidArgument);  // merge angle would round to pi
}

}  // namespace
}  // namespace rope
