// SPDX-License-Identifier: MIT
#pragma once
// The tractrix chain pass ([B] §2.1; docs/method.md §13): the leading point of a chain of rigid segments moves
// to a target; each segment's trailing point follows by the closed-form tractrix
// (tractrix_segment.h), and the new trailing point of segment i is the new leading point of segment
// i+1. One pass is O(n). Every segment keeps its length, and displacements decay along the chain:
// |dp_{i+1}| <= |dp_i| ([B] §2.1: dr_0 >= dr_1 >= ... >= dr_n).

#include <vector>

#include "rope/common/types.h"

namespace rope {

// points[0] is the leading point, points[i+1] trails segment i of rest length lengths[i] (metres).
// Moves points[0] to newLeading and every other point by the tractrix. Stops early once a point
// does not move (the rest of the chain then stays put exactly).
// Throws InvalidArgument, leaving points unchanged: "lengths.size()" not points.size() - 1 or
// points.size() < 2, "newLeading[c]" not finite or beyond kMaxTractrixCoordinate. The lengths themselves (finite, > 0) and distinct
// neighbouring points are the caller's invariant and are not re-checked on this hot path.
void tractrixChainPass(PointList& points, const std::vector<double>& lengths, const Vec3& newLeading);

// Validates a chain once, for callers that build one: "points[i][c]" not finite or beyond
// kMaxTractrixCoordinate, "lengths[i]" not
// finite and > 0. Distinct neighbours follow from the lengths only if the caller keeps them in step.
void validateTractrixChain(const PointList& points, const std::vector<double>& lengths);

}  // namespace rope
