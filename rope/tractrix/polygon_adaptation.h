// SPDX-License-Identifier: MIT
#pragma once
// Angle-threshold adaptation of a B-spline control polygon ([B] §3.1–3.3; docs/method.md §13): subdivision
// (knot insertion) cuts corners whose included angle is below a threshold, which leaves the curve
// exactly as it was and shortens the polygon; merging (knot removal) drops a knot where the polygon
// is nearly straight, which lengthens the polygon and moves the curve by the removal error. Both use
// the B-spline core's plans (knot_insertion.h, knot_removal.h), which keep the knots and the points
// in step. Angles in radians, lengths in metres.

#include <array>
#include <vector>

#include "rope/common/types.h"
#include "rope/spline/knot_removal.h"
#include "rope/spline/knot_vector.h"

namespace rope {

// One merge and its own error, as the core's removal plan reports it ([B] §3.2 eq. 23–24).
struct MergeRecord {
  double parameter = 0.0;                      // the removed knot value
  KnotRemoval::Side chosen = KnotRemoval::kFromLeft;
  std::array<double, 2> lengthError{};         // per candidate (left, right) sweep, metres
  std::array<double, 2> shapeError{};          // per candidate, metres (bounds the curve's displacement)
  double chosenLengthError() const { return lengthError[chosen]; }
  double chosenShapeError() const { return shapeError[chosen]; }
};

// Cuts the sharpest corner (included angle below subdivisionAngle) by inserting a knot in the
// middle of a span that removes it, and repeats until no corner is below the threshold or the
// polygon has maxControlPoints points. Of the spans that cut the corner, the one whose cut corners
// are the most bent is used; an insertion that would create a side shorter than minSide (metres) is
// skipped. Returns the number of insertions. The caller guarantees a valid, finite (knots, points)
// pair; throws only what the core throws.
int subdivideSharpCorners(KnotVector& knots, PointList& points, double subdivisionAngle, double minSide,
                          int maxControlPoints);

// What mergeStraightCorners may do.
struct MergeLimits {
  double mergingAngle = 0.0;   // radians: a knot is a candidate when all its corners are above this
  double guardAngle = 0.0;     // radians: reject a merge leaving an affected corner below this (0: off)
  double minSide = 0.0;        // metres: reject a merge leaving a side shorter than this
  double maxShapeError = 0.0;  // metres: reject a merge that moves the curve further than this
  int minControlPoints = 0;    // never merge below this count
};

// Removes knots whose affected corners (the control points the removal replaces) all have included
// angles above limits.mergingAngle, straightest first, while the polygon has more than
// limits.minControlPoints points. The core's plan picks the candidate with the smaller length error;
// a plan that breaks one of the other limits is rejected and the next knot is tried. Appends one
// MergeRecord per merge; returns their number.
int mergeStraightCorners(KnotVector& knots, PointList& points, const MergeLimits& limits,
                         std::vector<MergeRecord>& records);

}  // namespace rope
