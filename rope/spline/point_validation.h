// SPDX-License-Identifier: MIT
#pragma once
// Finiteness checks for control points and polyline points, shared by the spline module. They run
// before any arithmetic on the points: a NaN would otherwise raise the trapped "invalid" exception
// (or travel on silently) instead of being reported as bad input.

#include <cmath>
#include <cstddef>
#include <string>

#include "rope/common/error.h"
#include "rope/common/types.h"

namespace rope {

// "(x, y, z)" with full precision, for error messages.
inline std::string formatPoint(const Vec3& point) {
  return "(" + formatValue(point[0]) + ", " + formatValue(point[1]) + ", " + formatValue(point[2]) + ")";
}

// Throws InvalidArgument(name, "(x, y, z)") if a coordinate is NaN or infinite.
inline void requireFinitePoint(const std::string& name, const Vec3& point) {
  if (!(std::isfinite(point[0]) && std::isfinite(point[1]) && std::isfinite(point[2]))) {
    throw InvalidArgument(name, formatPoint(point), "coordinates must be finite");
  }
}

// Checks points[first..last] (inclusive) of an array of `count` points, naming the offending one
// "name[i]".
inline void requireFinitePoints(const char* name, const Vec3* points, std::size_t count, std::size_t first = 0,
                                std::size_t last = static_cast<std::size_t>(-1)) {
  if (count == 0) return;
  if (last >= count) last = count - 1;
  for (std::size_t i = first; i <= last; ++i) {
    const Vec3& p = points[i];
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) {
      throw InvalidArgument(std::string(name) + "[" + std::to_string(i) + "]", formatPoint(p), "coordinates must be finite");
    }
  }
}

// The same for a PointList.
inline void requireFinitePoints(const std::string& name, const PointList& points, std::size_t first = 0,
                                std::size_t last = static_cast<std::size_t>(-1)) {
  requireFinitePoints(name.c_str(), points.data(), points.size(), first, last);
}

}  // namespace rope
