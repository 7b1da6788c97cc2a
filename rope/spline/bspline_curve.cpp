// SPDX-License-Identifier: MIT
#include "rope/spline/bspline_curve.h"

#include <cmath>
#include <string>
#include <utility>

#include "rope/common/error.h"
#include "rope/spline/bspline_basis.h"
#include "rope/spline/curve_split.h"
#include "rope/spline/point_validation.h"

namespace rope {
namespace {

// Sum over the d+1 non-zero basis functions of span basis.span, up to derivative order Order.
template <int Order>
void accumulate(const BasisValues& basis, const PointList& points, CurvePoint& out) {
  const Vec3* q = points.data() + basis.firstIndex();
  Vec3 p = Vec3::Zero();
  Vec3 d1 = Vec3::Zero();
  Vec3 d2 = Vec3::Zero();
  for (int j = 0; j <= basis.degree; ++j) {
    p += basis.d[0][static_cast<size_t>(j)] * q[j];
    if constexpr (Order >= 1) d1 += basis.d[1][static_cast<size_t>(j)] * q[j];
    if constexpr (Order >= 2) d2 += basis.d[2][static_cast<size_t>(j)] * q[j];
  }
  out.position = p;
  out.firstDerivative = d1;
  out.secondDerivative = d2;
}

void accumulate(const BasisValues& basis, const PointList& points, int order, CurvePoint& out) {
  if (order <= 0) {
    accumulate<0>(basis, points, out);
  } else if (order == 1) {
    accumulate<1>(basis, points, out);
  } else {
    accumulate<2>(basis, points, out);
  }
}

}  // namespace

CurvePoint evaluateCurve(const KnotVector& knots, const PointList& points, double s) {
  int span = -1;  // no hint: a search
  return evaluateCurveNear(knots, points, s, span);
}

CurvePoint evaluateCurveNear(const KnotVector& knots, const PointList& points, double s, int& span) {
  if (!knots.contains(s)) knots.findSpan(s);  // throws InvalidArgument("s") as evaluateCurve does
  span = knots.findSpanNear(s, span);
  BasisValues basis;
  evaluateBasis(knots, span, s, kMaxBasisDerivative, basis);
  CurvePoint out;
  accumulate<kMaxBasisDerivative>(basis, points, out);
  return out;
}

Vec3 curvePosition(const KnotVector& knots, const PointList& points, double s) {
  int span = -1;  // no hint: a search
  return curvePositionNear(knots, points, s, span);
}

Vec3 curvePositionNear(const KnotVector& knots, const PointList& points, double s, int& span) {
  if (!knots.contains(s)) knots.findSpan(s);  // throws InvalidArgument("s") as curvePosition does
  span = knots.findSpanNear(s, span);
  BasisValues basis;
  evaluateBasis(knots, span, s, 0, basis);
  CurvePoint out;
  accumulate<0>(basis, points, out);
  return out.position;
}

BSplineCurve::BSplineCurve(KnotVector knots, PointList controlPoints)
    : knots_(std::move(knots)), points_(std::move(controlPoints)) {
  if (static_cast<int>(points_.size()) != knots_.controlPointCount()) {
    throw InvalidArgument("controlPoints.size()", std::to_string(points_.size()),
                          "must equal the knot vector's control point count " +
                              std::to_string(knots_.controlPointCount()));
  }
  requireFinitePoints("controlPoints", points_);
}

Vec3 BSplineCurve::position(double s) const { return curvePosition(knots_, points_, s); }

Vec3 BSplineCurve::derivative(double s, int order) const {
  if (order < 0 || order > kMaxBasisDerivative) {
    throw InvalidArgument("order", std::to_string(order), "must be in 0.." + std::to_string(kMaxBasisDerivative));
  }
  const int span = knots_.findSpan(s);
  BasisValues basis;
  evaluateBasis(knots_, span, s, order, basis);
  CurvePoint out;
  accumulate(basis, points_, order, out);
  if (order == 0) return out.position;
  return order == 1 ? out.firstDerivative : out.secondDerivative;
}

CurvePoint BSplineCurve::evaluate(double s) const { return evaluateCurve(knots_, points_, s); }

namespace {

void checkParameters(const KnotVector& knots, const std::vector<double>& s) {
  for (size_t i = 0; i < s.size(); ++i) {
    if (!knots.contains(s[i])) {
      throw InvalidArgument("s[" + std::to_string(i) + "]", formatValue(s[i]),
                            "must lie in the valid range [" + formatValue(knots.validBegin()) + ", " +
                                formatValue(knots.validEnd()) + "]");
    }
  }
}

}  // namespace

void BSplineCurve::evaluate(const std::vector<double>& s, std::vector<CurvePoint>& out) const {
  checkParameters(knots_, s);
  out.resize(s.size());
  BasisValues basis;
  int span = -1;
  for (size_t i = 0; i < s.size(); ++i) {
    span = knots_.findSpanNear(s[i], span);  // sorted input never searches
    evaluateBasis(knots_, span, s[i], kMaxBasisDerivative, basis);
    accumulate<kMaxBasisDerivative>(basis, points_, out[i]);
  }
}

void BSplineCurve::positions(const std::vector<double>& s, PointList& out) const {
  curvePositions(knots_, points_, s, out);
}

void curvePositions(const KnotVector& knots, const PointList& points, const std::vector<double>& s, PointList& out) {
  checkParameters(knots, s);
  out.resize(s.size());
  BasisValues basis;
  CurvePoint point;
  int span = -1;
  for (size_t i = 0; i < s.size(); ++i) {
    span = knots.findSpanNear(s[i], span);  // sorted input never searches
    evaluateBasis(knots, span, s[i], 0, basis);
    accumulate<0>(basis, points, point);
    out[i] = point.position;
  }
}

void BSplineCurve::setControlPoint(int i, const Vec3& point) {
  if (i < 0 || i >= controlPointCount()) {
    throw InvalidArgument("i", std::to_string(i), "must be in 0.." + std::to_string(controlPointCount() - 1));
  }
  requireFinitePoint("point", point);
  points_[static_cast<size_t>(i)] = point;
}

void BSplineCurve::setControlPoints(PointList points) {
  if (points.size() != points_.size()) {
    throw InvalidArgument("points.size()", std::to_string(points.size()),
                          "must equal the control point count " + std::to_string(points_.size()));
  }
  requireFinitePoints("points", points);
  points_ = std::move(points);
}

KnotInsertion BSplineCurve::insertKnot(double s) { return rope::insertKnot(knots_, points_, s); }

KnotRemoval BSplineCurve::removeKnot(double s) { return rope::removeKnot(knots_, points_, s); }

std::pair<BSplineCurve, BSplineCurve> BSplineCurve::split(double s) const {
  const CurveSplitPlan plan = planCurveSplit(knots_, s);
  auto pieces = plan.apply(points_);
  return {BSplineCurve(plan.leftKnots, std::move(pieces.first)),
          BSplineCurve(plan.rightKnots, std::move(pieces.second))};
}

}  // namespace rope
