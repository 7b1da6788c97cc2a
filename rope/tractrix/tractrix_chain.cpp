// SPDX-License-Identifier: MIT
#include "rope/tractrix/tractrix_chain.h"

#include <string>

#include "rope/common/error.h"
#include "rope/tractrix/tractrix_segment.h"

namespace rope {

void tractrixChainPass(PointList& points, const std::vector<double>& lengths, const Vec3& newLeading) {
  if (points.size() < 2) {
    throw InvalidArgument("points.size()", std::to_string(points.size()), "a chain needs at least 2 points");
  }
  if (lengths.size() + 1 != points.size()) {
    throw InvalidArgument("lengths.size()", std::to_string(lengths.size()),
                          "must be points.size() - 1 = " + std::to_string(points.size() - 1));
  }
  for (int c = 0; c < 3; ++c) requireTractrixCoordinate("newLeading[" + std::to_string(c) + "]", newLeading[c]);

  Vec3 oldLeading = points[0];
  points[0] = newLeading;
  const size_t segments = lengths.size();
  for (size_t i = 0; i < segments; ++i) {
    const Vec3 oldTrailing = points[i + 1];
    // [B] §2.1: the trailing point of segment i is the leading point of segment i+1.
    const Vec3 moved = tractrixMoveTrailing(oldLeading, oldTrailing, points[i], lengths[i]);
    if (moved == oldTrailing) break;  // nothing further down moves
    points[i + 1] = moved;
    oldLeading = oldTrailing;
  }
}

void validateTractrixChain(const PointList& points, const std::vector<double>& lengths) {
  if (points.size() < 2) {
    throw InvalidArgument("points.size()", std::to_string(points.size()), "a chain needs at least 2 points");
  }
  if (lengths.size() + 1 != points.size()) {
    throw InvalidArgument("lengths.size()", std::to_string(lengths.size()),
                          "must be points.size() - 1 = " + std::to_string(points.size() - 1));
  }
  for (size_t i = 0; i < points.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      requireTractrixCoordinate("points[" + std::to_string(i) + "][" + std::to_string(c) + "]", points[i][c]);
    }
  }
  for (size_t i = 0; i < lengths.size(); ++i) requirePositive("lengths[" + std::to_string(i) + "]", lengths[i]);
}

}  // namespace rope
