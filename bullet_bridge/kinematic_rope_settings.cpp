// SPDX-License-Identifier: MIT
#include "bullet_bridge/kinematic_rope_settings.h"

#include <string>

#include "rope/common/error.h"

namespace rope::bullet {

void KinematicRopeSettings::validate() const {
  requirePositive("settings.radius", radius);
  if (radius > kMaxSize) throw InvalidArgument("settings.radius", formatValue(radius), "must be <= 1e5 (m)");
  if (capsulesPerSpan < 1 || capsulesPerSpan > 64) {
    throw InvalidArgument("settings.capsulesPerSpan", std::to_string(capsulesPerSpan), "must be in [1, 64]");
  }
  requireNonNegative("settings.speculativeMargin", speculativeMargin);
  if (speculativeMargin > kMaxSize) {
    throw InvalidArgument("settings.speculativeMargin", formatValue(speculativeMargin), "must be <= 1e5 (m)");
  }
  requirePositive("settings.penetrationRecovery", penetrationRecovery);
  if (penetrationRecovery > 1.0) {
    throw InvalidArgument("settings.penetrationRecovery", formatValue(penetrationRecovery), "must be <= 1");
  }
  requireNonNegative("settings.friction", friction);
  if (solverIterations < 1 || solverIterations > 1000) {
    throw InvalidArgument("settings.solverIterations", std::to_string(solverIterations), "must be in [1, 1000]");
  }
  if (collisionGroup == 0) {
    throw InvalidArgument("settings.collisionGroup", "0", "must have at least one bit set");
  }
}

}  // namespace rope::bullet
