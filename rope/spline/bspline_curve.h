// SPDX-License-Identifier: MIT
#pragma once
// A B-spline curve C(s) = sum_i q_i b_{i,d}(s) in R^3 (docs/method.md §1, eq. 1). Metres.

#include <utility>
#include <vector>

#include "rope/common/types.h"
#include "rope/spline/knot_insertion.h"
#include "rope/spline/knot_removal.h"
#include "rope/spline/knot_vector.h"

namespace rope {

struct CurvePoint {
  Vec3 position = Vec3::Zero();          // C(s)
  Vec3 firstDerivative = Vec3::Zero();   // C'(s)
  Vec3 secondDerivative = Vec3::Zero();  // C''(s)
};

// Free functions on (knots, points), for owners that keep their own arrays (the rod, tractrix).
// They validate s (InvalidArgument "s") but assume points.size() == knots.controlPointCount().
CurvePoint evaluateCurve(const KnotVector& knots, const PointList& points, double s);
Vec3 curvePosition(const KnotVector& knots, const PointList& points, double s);
// evaluateCurve(s), bitwise, with the span search started from `span` (as curvePositionNear).
CurvePoint evaluateCurveNear(const KnotVector& knots, const PointList& points, double s, int& span);
// curvePosition(s), bitwise, with the span search started from `span` (KnotVector::findSpanNear), which
// is set to s's span: for a caller that asks for points in order along the curve or within one span.
Vec3 curvePositionNear(const KnotVector& knots, const PointList& points, double s, int& span);
// curvePosition at every s[i], into out (resized): bitwise the same values, but sorted parameters
// reuse the previous span instead of searching (any order is correct). Every s is validated
// (InvalidArgument "s[i]") before anything is written.
void curvePositions(const KnotVector& knots, const PointList& points, const std::vector<double>& s, PointList& out);

class BSplineCurve {
 public:
  // Throws InvalidArgument: "controlPoints.size()" not equal to knots.controlPointCount(), or
  // "controlPoints[i]" with a non-finite coordinate.
  BSplineCurve(KnotVector knots, PointList controlPoints);

  const KnotVector& knots() const { return knots_; }
  const PointList& controlPoints() const { return points_; }
  int degree() const { return knots_.degree(); }
  int controlPointCount() const { return static_cast<int>(points_.size()); }
  double beginParameter() const { return knots_.validBegin(); }
  double endParameter() const { return knots_.validEnd(); }

  // Throw InvalidArgument("s", ...) outside [beginParameter, endParameter] or for NaN.
  Vec3 position(double s) const;
  Vec3 derivative(double s, int order = 1) const;  // order 0..2 ("order")
  CurvePoint evaluate(double s) const;

  // Batch evaluation: out is resized to s.size(). Every s is validated before anything is written.
  // Sorted parameters reuse the previous span (no search), any order is correct.
  void evaluate(const std::vector<double>& s, std::vector<CurvePoint>& out) const;
  void positions(const std::vector<double>& s, PointList& out) const;

  // Throws for i out of range ("i") or a non-finite point ("point"); nothing changes on error.
  void setControlPoint(int i, const Vec3& point);
  // Same count required ("points.size()"); all-or-nothing.
  void setControlPoints(PointList points);

  // Exact Boehm insertion of s (see knot_insertion.h); the curve does not change shape.
  KnotInsertion insertKnot(double s);
  // Removes one occurrence of the knot s, applying the candidate with the smaller length error and
  // returning both candidates' errors (see knot_removal.h). Shape changes by at most shapeError().
  KnotRemoval removeKnot(double s);
  // Two independent curves meeting at C(s) (see curve_split.h). Throws for s not strictly inside.
  std::pair<BSplineCurve, BSplineCurve> split(double s) const;

 private:
  KnotVector knots_;
  PointList points_;
};

}  // namespace rope
