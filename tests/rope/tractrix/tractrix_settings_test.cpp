// SPDX-License-Identifier: MIT
// Validation of TractrixSettings: every field's bad values are rejected with its name.
#include "rope/tractrix/tractrix_settings.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "rope/common/error.h"

namespace rope {
namespace {

// Expects validateTractrixSettings to throw InvalidArgument naming `parameter` after `change`.
void expectRejected(const std::function<void(TractrixSettings&)>& change, const std::string& parameter) {
  TractrixSettings settings;
  change(settings);
  try {
    validateTractrixSettings(settings);
    ADD_FAILURE() << parameter << ": accepted";
  } catch (const InvalidArgument& error) {
    EXPECT_EQ(error.parameter(), parameter) << error.what();
  }
}

TEST(TractrixSettings, DefaultsAreThePapersAndValid) {
  const TractrixSettings settings;
  EXPECT_NO_THROW(validateTractrixSettings(settings));
  EXPECT_EQ(settings.variant, TractrixVariant::kSplineSubdivideMerge);
  EXPECT_EQ(settings.segmentCount, 6);
  EXPECT_EQ(settings.degree, 3);
  EXPECT_NEAR(toDegrees(settings.subdivisionAngle), 140.0, 1e-12);
  EXPECT_NEAR(toDegrees(settings.mergingAngle), 160.0, 1e-12);
  EXPECT_EQ(settings.effectiveMinControlPoints(), 7);
  // Beyond [B]: the curve keeps its length unless asked for the paper's behaviour.
  EXPECT_EQ(settings.lengthCorrection, TractrixLengthCorrection::kRestoreCurveLength);
}

TEST(TractrixSettings, DegreeHelpers) {
  TractrixSettings settings;
  settings.setThresholdsDegrees(150.0, 170.0);
  EXPECT_DOUBLE_EQ(settings.subdivisionAngle, 150.0 * kTractrixPi / 180.0);
  EXPECT_DOUBLE_EQ(settings.mergingAngle, 170.0 * kTractrixPi / 180.0);
  EXPECT_DOUBLE_EQ(toDegrees(degrees(33.0)), 33.0);
}

TEST(TractrixSettings, RejectsBadThresholds) {
  const double nan = std::nan("");
  expectRejected([&](TractrixSettings& s) { s.subdivisionAngle = nan; }, "settings.subdivisionAngle");
  expectRejected([&](TractrixSettings& s) { s.mergingAngle = HUGE_VAL; }, "settings.mergingAngle");
  expectRejected([](TractrixSettings& s) { s.subdivisionAngle = 0.0; }, "settings.subdivisionAngle");
  expectRejected([](TractrixSettings& s) { s.subdivisionAngle = -1.0; }, "settings.subdivisionAngle");
  // Out of order, equal, and at/above pi (degrees passed where radians are expected).
  expectRejected([](TractrixSettings& s) { s.setThresholdsDegrees(160.0, 140.0); }, "settings.mergingAngle");
  expectRejected([](TractrixSettings& s) { s.setThresholdsDegrees(150.0, 150.0); }, "settings.mergingAngle");
  expectRejected([](TractrixSettings& s) { s.setThresholdsDegrees(140.0, 180.0); }, "settings.mergingAngle");
  expectRejected([](TractrixSettings& s) {
    s.subdivisionAngle = 140.0;
    s.mergingAngle = 160.0;
  }, "settings.mergingAngle");
}

TEST(TractrixSettings, RejectsBadCounts) {
  expectRejected([](TractrixSettings& s) { s.segmentCount = 2; }, "settings.segmentCount");  // < degree
  expectRejected([](TractrixSettings& s) { s.degree = 1; }, "settings.degree");
  expectRejected([](TractrixSettings& s) { s.degree = 6; }, "settings.degree");
  expectRejected([](TractrixSettings& s) { s.minControlPoints = 3; }, "settings.minControlPoints");
  expectRejected([](TractrixSettings& s) { s.minControlPoints = 8; }, "settings.minControlPoints");
  expectRejected([](TractrixSettings& s) { s.maxControlPoints = 6; }, "settings.maxControlPoints");
  expectRejected([](TractrixSettings& s) { s.lengthGaussPoints = 0; }, "settings.lengthGaussPoints");
  expectRejected([](TractrixSettings& s) { s.maxMergeShapeError = 0.0; }, "settings.maxMergeShapeError");
  expectRejected([](TractrixSettings& s) { s.maxMergeShapeError = std::nan(""); }, "settings.maxMergeShapeError");
  expectRejected([](TractrixSettings& s) { s.lengthGaussPoints = 33; }, "settings.lengthGaussPoints");
  expectRejected([](TractrixSettings& s) { s.variant = static_cast<TractrixVariant>(7); }, "settings.variant");
  expectRejected([](TractrixSettings& s) { s.lengthCorrection = static_cast<TractrixLengthCorrection>(2); },
                 "settings.lengthCorrection");
  expectRejected([](TractrixSettings& s) {
    s.variant = TractrixVariant::kPolyline;
    s.segmentCount = 0;
  }, "settings.segmentCount");
}

TEST(TractrixSettings, PolylineIgnoresSplineOnlyFields) {
  TractrixSettings settings;
  settings.variant = TractrixVariant::kPolyline;
  settings.segmentCount = 1;
  settings.degree = 9;
  settings.minControlPoints = 100;
  settings.maxControlPoints = 1;
  EXPECT_NO_THROW(validateTractrixSettings(settings));
}

}  // namespace
}  // namespace rope
