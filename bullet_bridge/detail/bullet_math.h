// SPDX-License-Identifier: MIT
#pragma once
// Conversions between Bullet's vectors (btScalar: float or double, per the Bullet build) and the
// rope's Eigen vectors (double), and finiteness checks of Bullet values. Internal: one definition for
// every file of the bridge that crosses the boundary.

#include <LinearMath/btTransform.h>
#include <LinearMath/btVector3.h>

#include <cmath>

#include "rope/common/types.h"

namespace rope::bullet {

inline Vec3 toVec(const btVector3& v) {
  return Vec3(static_cast<double>(v.x()), static_cast<double>(v.y()), static_cast<double>(v.z()));
}

inline btVector3 toBullet(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()), static_cast<btScalar>(v.z()));
}

inline bool isFinite(const btVector3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

inline bool isFinite(const btTransform& t) {
  return isFinite(t.getOrigin()) && isFinite(t.getBasis()[0]) && isFinite(t.getBasis()[1]) &&
         isFinite(t.getBasis()[2]);
}

}  // namespace rope::bullet
