// SPDX-License-Identifier: MIT
// Rod: cutting ([A] §5.1; docs/method.md §4): raising the multiplicity of s to d+1 by exact insertion makes the
// curve C^-1 there; no basis function spans s, so the two sides share no mass, energy or force term and
// become two independent rods. Positions, velocities and the rest curve follow the same exact map, so
// mass, momentum and every energy are split without loss.
#include <algorithm>
#include <string>

#include "rope/common/error.h"
#include "rope/rod/rod.h"
#include "rope/spline/curve_split.h"

namespace rope {

std::pair<Rod, Rod> Rod::cut(double requested) const {
  const double s = cutPoint(requested);
  for (const Pin& p : pins_) {
    if (p.parameter == s) throw InvalidArgument("s", formatValue(s), "a pin is at the cut");
  }
  const CurveSplitPlan plan = planCurveSplit(knots_, s);  // throws for s at an end
  auto points = plan.apply(points_);
  auto velocities = plan.apply(velocities_);
  auto rest = plan.apply(rest_);

  auto makePiece = [&](const KnotVector& knots, PointList& q, PointList& v, PointList& r) {
    RodSettings settings = settings_;
    const int count = static_cast<int>(q.size());
    settings.minControlPoints = std::min(settings.minControlPoints, count);
    settings.maxControlPoints = std::max(settings.maxControlPoints, count);
    settings.initialControlPoints = count;
    Rod piece(settings, knots, std::move(q), std::move(v), std::move(r), integrals_.gaussCount());
    piece.settings_.restLength = piece.restLength();
    return piece;
  };
  Rod left = makePiece(plan.leftKnots, points.first, velocities.first, rest.first);
  Rod right = makePiece(plan.rightKnots, points.second, velocities.second, rest.second);
  for (const Pin& p : pins_) {
    Rod& piece = p.parameter < s ? left : right;
    piece.pins_.push_back(p);  // ids are kept
  }
  left.nextPinId_ = nextPinId_;
  right.nextPinId_ = nextPinId_;
  for (const auto& pointMass : pointMasses_) (pointMass.first <= s ? left : right).pointMasses_.push_back(pointMass);
  for (const PointLoad& load : loads_) (load.parameter <= s ? left : right).loads_.push_back(load);
  for (const Spring& spring : springs_) (spring.parameter <= s ? left : right).springs_.push_back(spring);
  return {std::move(left), std::move(right)};
}

}  // namespace rope
