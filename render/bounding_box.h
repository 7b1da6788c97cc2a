// SPDX-License-Identifier: MIT
#pragma once
// Axis-aligned bounding box in world coordinates (metres). A default box is empty and absorbs
// whatever is added to it.

#include <limits>

#include "rope/common/types.h"

namespace rope::render {

struct BoundingBox {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());

  bool empty() const { return !(min.x() <= max.x() && min.y() <= max.y() && min.z() <= max.z()); }
  void extend(const Vec3& point) {
    min = min.cwiseMin(point);
    max = max.cwiseMax(point);
  }
  void extend(const BoundingBox& other) {
    if (other.empty()) return;
    extend(other.min);
    extend(other.max);
  }
  // Only meaningful for a non-empty box.
  Vec3 center() const { return 0.5 * (min + max); }
  double radius() const { return 0.5 * (max - min).norm(); }
};

}  // namespace rope::render
