// SPDX-License-Identifier: MIT
#include "rope/rod/rod_settings.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "rope/common/error.h"
#include "rope/spline/control_polygon.h"

namespace rope {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(RodSettings, DefaultsAreValidAndDocumented) {
  const RodSettings settings;
  EXPECT_NO_THROW(settings.validate());
  EXPECT_NEAR(settings.area(), kPi * 0.005 * 0.005, 1e-18);
  EXPECT_NEAR(settings.effectiveLinearDensity(), 1150.0 * kPi * 2.5e-5, 1e-15);
  EXPECT_NEAR(settings.axialStiffness(), 1e9 * kPi * 2.5e-5, 1e-6);
  EXPECT_NEAR(settings.effectiveBendingStiffness(), 1e9 * kPi * std::pow(0.005, 4) / 4.0, 1e-12);
  // [B]'s thresholds as bend measures (docs/method.md eq. 28): 140 deg -> 0.117, 160 deg -> 0.030.
  EXPECT_NEAR(bendMeasureFromAngle(settings.insertAngle), 0.117, 5e-4);
  EXPECT_NEAR(bendMeasureFromAngle(settings.removeAngle), 0.030, 5e-4);
}

TEST(RodSettings, ExplicitValuesOverrideDerivedOnes) {
  RodSettings settings;
  settings.linearDensity = 0.01;
  settings.bendingStiffness = 0.0;  // [A]: stretching only
  EXPECT_NO_THROW(settings.validate());
  EXPECT_EQ(settings.effectiveLinearDensity(), 0.01);
  EXPECT_EQ(settings.effectiveBendingStiffness(), 0.0);
}

struct BadCase {
  std::string parameter;
  std::function<void(RodSettings&)> corrupt;
};

TEST(RodSettings, EveryBadValueNamesItsField) {
  const std::vector<BadCase> cases = {
      {"settings.restLength", [](RodSettings& s) { s.restLength = 0.0; }},
      {"settings.restLength", [](RodSettings& s) { s.restLength = -1.0; }},
      {"settings.restLength", [](RodSettings& s) { s.restLength = kNaN; }},
      {"settings.radius", [](RodSettings& s) { s.radius = 0.0; }},
      {"settings.radius", [](RodSettings& s) { s.radius = kInf; }},
      {"settings.linearDensity", [](RodSettings& s) { s.linearDensity = -2.0; }},
      {"settings.linearDensity", [](RodSettings& s) { s.linearDensity = 0.0; }},
      {"settings.linearDensity", [](RodSettings& s) { s.linearDensity = kNaN; }},
      {"settings.materialDensity", [](RodSettings& s) { s.materialDensity = 0.0; }},
      {"settings.youngsModulus", [](RodSettings& s) { s.youngsModulus = -1e9; }},
      {"settings.youngsModulus", [](RodSettings& s) { s.youngsModulus = kNaN; }},
      {"settings.bendingStiffness", [](RodSettings& s) { s.bendingStiffness = -0.5; }},
      {"settings.bendingStiffness", [](RodSettings& s) { s.bendingStiffness = kNaN; }},
      {"settings.massDamping", [](RodSettings& s) { s.massDamping = -1.0; }},
      {"settings.stiffnessDamping", [](RodSettings& s) { s.stiffnessDamping = kNaN; }},
      {"settings.gravity[1]", [](RodSettings& s) { s.gravity.y() = kNaN; }},
      {"settings.degree", [](RodSettings& s) { s.degree = 0; }},
      {"settings.degree", [](RodSettings& s) { s.degree = 9; }},
      {"settings.minControlPoints", [](RodSettings& s) { s.minControlPoints = 3; }},
      {"settings.maxControlPoints", [](RodSettings& s) { s.maxControlPoints = 3; }},
      {"settings.initialControlPoints", [](RodSettings& s) { s.initialControlPoints = 200; }},
      {"settings.initialControlPoints", [](RodSettings& s) { s.initialControlPoints = 2; }},
      {"settings.insertAngle", [](RodSettings& s) { s.insertAngle = 0.0; }},
      {"settings.removeAngle", [](RodSettings& s) { s.removeAngle = 2.0; }},  // < insertAngle
      {"settings.removeAngle", [](RodSettings& s) { s.removeAngle = kPi; }},
      {"settings.removeAngle", [](RodSettings& s) { s.removeAngle = kNaN; }},
      {"settings.removalErrorBound", [](RodSettings& s) { s.removalErrorBound = 0.0; }},
      {"settings.removalVelocityErrorBound", [](RodSettings& s) { s.removalVelocityErrorBound = 0.0; }},
      {"settings.removalVelocityErrorBound", [](RodSettings& s) { s.removalVelocityErrorBound = kNaN; }},
      {"settings.minKnotSpacing", [](RodSettings& s) { s.minKnotSpacing = -1.0; }},
  };
  for (const BadCase& bad : cases) {
    RodSettings settings;
    bad.corrupt(settings);
    try {
      settings.validate();
      ADD_FAILURE() << "no exception for " << bad.parameter;
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.parameter(), bad.parameter) << e.what();
    }
  }
}

}  // namespace
}  // namespace rope
