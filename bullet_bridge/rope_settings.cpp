// SPDX-License-Identifier: MIT
#include "bullet_bridge/rope_settings.h"

#include <cmath>
#include <string>

#include "rope/common/error.h"

namespace rope::bullet {

void BulletRopeSettings::validate() const {
  requirePositive("settings.lineContactStiffness", lineContactStiffness);
  requireNonNegative("settings.lineContactDamping", lineContactDamping);
  requireNonNegative("settings.lineSpeculativeDamping", lineSpeculativeDamping);
  if (contactQuadraturePoints < 1 || contactQuadraturePoints > 8) {
    throw InvalidArgument("settings.contactQuadraturePoints", std::to_string(contactQuadraturePoints),
                          "must be in [1, 8]");
  }
  requirePositive("settings.concentratedContactRatio", concentratedContactRatio);
  if (concentratedContactRatio > 1.0) {
    throw InvalidArgument("settings.concentratedContactRatio", formatValue(concentratedContactRatio),
                          "must be <= 1");
  }
  requireFinite("settings.gravityScale", gravityScale);
  if (gravitySource != GravitySource::kWorld && gravitySource != GravitySource::kRod) {
    throw InvalidArgument("settings.gravitySource", std::to_string(static_cast<int>(gravitySource)),
                          "must be kWorld or kRod");
  }
  requireNonNegative("settings.fluidDensity", fluidDensity);
  requireNonNegative("settings.normalDragCoefficient", normalDragCoefficient);
  requireNonNegative("settings.tangentialDragCoefficient", tangentialDragCoefficient);
  requireFinite("settings.windVelocity.x", static_cast<double>(windVelocity.x()));
  requireFinite("settings.windVelocity.y", static_cast<double>(windVelocity.y()));
  requireFinite("settings.windVelocity.z", static_cast<double>(windVelocity.z()));
  requirePositive("settings.contactStiffness", contactStiffness);
  requireNonNegative("settings.contactDamping", contactDamping);
  requireNonNegative("settings.speculativeDamping", speculativeDamping);
  requireNonNegative("settings.friction", friction);
  requirePositive("settings.frictionVelocity", frictionVelocity);
  if (capsulesPerSpan < 1 || capsulesPerSpan > 16) {
    throw InvalidArgument("settings.capsulesPerSpan", std::to_string(capsulesPerSpan), "must be in [1, 16]");
  }
  requireNonNegative("settings.speculativeMargin", speculativeMargin);
  requirePositive("settings.initialPredictionTime", initialPredictionTime);
  requirePositive("settings.bodyStabilityFactor", bodyStabilityFactor);
  if (bodyStabilityFactor > 1.0) {
    throw InvalidArgument("settings.bodyStabilityFactor", formatValue(bodyStabilityFactor), "must be <= 1");
  }
  requireFinite("settings.selfContactExclusion", selfContactExclusion);
  if (selfContactExclusion < 0.0 && selfContactExclusion != kDerivedExclusion) {
    throw InvalidArgument("settings.selfContactExclusion", formatValue(selfContactExclusion),
                          "must be >= 0 (m) or kDerivedExclusion");
  }
  if (collisionGroup == 0) {
    throw InvalidArgument("settings.collisionGroup", "0", "must have at least one bit set");
  }
}

}  // namespace rope::bullet
