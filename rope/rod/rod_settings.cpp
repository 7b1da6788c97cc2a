// SPDX-License-Identifier: MIT
#include "rope/rod/rod_settings.h"

#include <cmath>
#include <limits>
#include <string>

#include "rope/common/error.h"
#include "rope/spline/knot_vector.h"

namespace rope {

namespace {
constexpr double kPi = 3.14159265358979323846;

void requireDouble(const char* name, long double value, const std::string& shown) {
  if (!(value <= static_cast<long double>(std::numeric_limits<double>::max()))) {
    throw InvalidArgument(name, shown, "overflows a double");
  }
}

// The derived quantities of validated (finite, positive) fields, without overflowing on the way.
void requireRepresentable(const RodSettings& s) {
  const long double r = s.radius;
  const long double area = static_cast<long double>(kPi) * r * r;
  requireDouble("settings.radius", area, formatValue(s.radius) + " (area pi r^2)");
  if (s.linearDensity == RodSettings::kDerived) {
    requireDouble("settings.materialDensity", s.materialDensity * area, formatValue(s.materialDensity) + " (times the area)");
  }
  requireDouble("settings.youngsModulus", s.youngsModulus * area, formatValue(s.youngsModulus) + " (times the area)");
  if (s.bendingStiffness == RodSettings::kDerived) {
    requireDouble("settings.youngsModulus", s.youngsModulus * area * area / (4.0L * static_cast<long double>(kPi)),
                  formatValue(s.youngsModulus) + " (times the area moment pi r^4 / 4)");
  }
}

void requireCount(const std::string& name, int value, int lowest) {
  if (value < lowest) {
    throw InvalidArgument(name, std::to_string(value), "must be >= " + std::to_string(lowest));
  }
}
}  // namespace

double RodSettings::area() const { return kPi * radius * radius; }

double RodSettings::effectiveLinearDensity() const {
  return linearDensity == kDerived ? materialDensity * area() : linearDensity;
}

double RodSettings::axialStiffness() const { return youngsModulus * area(); }

double RodSettings::effectiveBendingStiffness() const {
  // Solid circular section: I = pi r^4 / 4.
  return bendingStiffness == kDerived ? youngsModulus * kPi * radius * radius * radius * radius / 4.0
                                      : bendingStiffness;
}

void RodSettings::validate() const {
  requirePositive("settings.restLength", restLength);
  requirePositive("settings.radius", radius);
  requireFinite("settings.linearDensity", linearDensity);
  if (linearDensity == kDerived) {
    requirePositive("settings.materialDensity", materialDensity);
  } else {
    requirePositive("settings.linearDensity", linearDensity);
  }
  requirePositive("settings.youngsModulus", youngsModulus);
  requireFinite("settings.bendingStiffness", bendingStiffness);
  if (bendingStiffness != kDerived) requireNonNegative("settings.bendingStiffness", bendingStiffness);
  requireNonNegative("settings.massDamping", massDamping);
  requireNonNegative("settings.stiffnessDamping", stiffnessDamping);
  requireNonNegative("settings.materialDamping", materialDamping);
  if (timeIntegrator != TimeIntegrator::kBdf2 && timeIntegrator != TimeIntegrator::kBackwardEuler) {
    throw InvalidArgument("settings.timeIntegrator", std::to_string(static_cast<int>(timeIntegrator)),
                          "is not a TimeIntegrator");
  }
  for (int axis = 0; axis < 3; ++axis) {
    requireFinite("settings.gravity[" + std::to_string(axis) + "]", gravity[axis]);
  }
  if (degree < 1 || degree > kMaxDegree) {
    throw InvalidArgument("settings.degree", std::to_string(degree),
                          "must be in 1.." + std::to_string(kMaxDegree));
  }
  if (stretchingQuadrature != StretchingQuadrature::kExact && stretchingQuadrature != StretchingQuadrature::kLockingFree) {
    throw InvalidArgument("settings.stretchingQuadrature", std::to_string(static_cast<int>(stretchingQuadrature)),
                          "is not a StretchingQuadrature");
  }
  requireCount("settings.minControlPoints", minControlPoints, degree + 1);
  requireCount("settings.maxControlPoints", maxControlPoints, minControlPoints);
  if (maxControlPoints > kMaxControlPointsLimit) {
    // Found by fuzzing: 2^30 was accepted and fromSegment then asked for 8 GB of knots.
    throw InvalidArgument("settings.maxControlPoints", std::to_string(maxControlPoints),
                          "must be <= " + std::to_string(kMaxControlPointsLimit));
  }
  requireCount("settings.initialControlPoints", initialControlPoints, minControlPoints);
  if (initialControlPoints > maxControlPoints) {
    throw InvalidArgument("settings.initialControlPoints", std::to_string(initialControlPoints),
                          "must be <= settings.maxControlPoints");
  }
  requirePositive("settings.insertAngle", insertAngle);
  requireFinite("settings.removeAngle", removeAngle);
  if (!(removeAngle > insertAngle) || !(removeAngle < kPi)) {
    throw InvalidArgument("settings.removeAngle", formatValue(removeAngle),
                          "must satisfy settings.insertAngle < removeAngle < pi");
  }
  requirePositive("settings.removalErrorBound", removalErrorBound);
  requirePositive("settings.removalVelocityErrorBound", removalVelocityErrorBound);
  if (removalCriterion != RemovalCriterion::kPolygon && removalCriterion != RemovalCriterion::kMechanical &&
      removalCriterion != RemovalCriterion::kMechanicalOutOfContact) {
    throw InvalidArgument("settings.removalCriterion", std::to_string(static_cast<int>(removalCriterion)),
                          "is not a RemovalCriterion");
  }
  requirePositive("settings.removalRelativeError", removalRelativeError);
  if (!(removalRelativeError < 1.0)) {
    throw InvalidArgument("settings.removalRelativeError", formatValue(removalRelativeError), "must be < 1");
  }
  requirePositive("settings.minKnotSpacing", minKnotSpacing);
  // Derived quantities must be usable too (e.g. a radius so small that EA underflows to 0), and
  // computing them must not overflow (a radius of 1e200 m): checked in long double first, whose range
  // holds any product of these doubles.
  requireRepresentable(*this);
  requirePositive("settings.linearDensity (derived)", effectiveLinearDensity());
  requirePositive("settings.youngsModulus * area", axialStiffness());
  requireNonNegative("settings.bendingStiffness (derived)", effectiveBendingStiffness());
}

}  // namespace rope
