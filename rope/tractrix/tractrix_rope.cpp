// SPDX-License-Identifier: MIT
#include "rope/tractrix/tractrix_rope.h"

#include <cmath>
#include <string>
#include <utility>

#include "rope/common/error.h"
#include "rope/spline/arc_length.h"
#include "rope/spline/control_polygon.h"
#include "rope/spline/curve_interpolation.h"
#include "rope/tractrix/length_correction.h"
#include "rope/tractrix/tractrix_chain.h"
#include "rope/tractrix/tractrix_segment.h"

namespace rope {

struct TractrixRope::Initial {
  TractrixSettings settings;
  KnotVector knots;
  PointList points;
};

namespace {

std::string pointText(const Vec3& p) {
  return "(" + formatValue(p.x()) + ", " + formatValue(p.y()) + ", " + formatValue(p.z()) + ")";
}

// count + 1 points equally spaced in arc length along the polyline, ends included exactly.
PointList resample(const PointList& shape, const std::vector<double>& cumulative, int count) {
  const double total = cumulative.back();
  PointList samples;
  samples.reserve(static_cast<size_t>(count) + 1);
  samples.push_back(shape.front());
  size_t piece = 1;  // cumulative[piece - 1] <= target <= cumulative[piece]
  for (int j = 1; j < count; ++j) {
    const double target = total * j / count;
    while (piece + 1 < cumulative.size() && cumulative[piece] < target) ++piece;
    const double t = (target - cumulative[piece - 1]) / (cumulative[piece] - cumulative[piece - 1]);
    samples.push_back(shape[piece - 1] + t * (shape[piece] - shape[piece - 1]));
  }
  samples.push_back(shape.back());
  return samples;
}

// Degree-1 clamped knots at the cumulative side lengths: the polyline as a B-spline, s = arc length.
KnotVector polylineKnots(const PointList& points) {
  std::vector<double> values;
  values.reserve(points.size() + 2);
  values.push_back(0.0);
  double s = 0.0;
  values.push_back(s);
  for (size_t i = 1; i < points.size(); ++i) {
    s += (points[i] - points[i - 1]).norm();
    values.push_back(s);
  }
  values.push_back(s);
  return KnotVector(1, std::move(values));
}

}  // namespace

TractrixRope::Initial TractrixRope::initialize(const PointList& shape, const TractrixSettings& settings) {
  validateTractrixSettings(settings);
  if (shape.size() < 2) {
    throw InvalidArgument("initialShape.size()", std::to_string(shape.size()), "must be >= 2");
  }
  std::vector<double> cumulative(shape.size(), 0.0);
  for (size_t i = 0; i < shape.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      requireTractrixCoordinate("initialShape[" + std::to_string(i) + "][" + std::to_string(c) + "]", shape[i][c]);
    }
    if (i == 0) continue;
    const double side = (shape[i] - shape[i - 1]).norm();
    if (!(side > 0.0)) {
      throw InvalidArgument("initialShape[" + std::to_string(i) + "]", pointText(shape[i]),
                            "must differ from initialShape[" + std::to_string(i - 1) + "]");
    }
    cumulative[i] = cumulative[i - 1] + side;
  }

  PointList samples = resample(shape, cumulative, settings.segmentCount);
  for (size_t i = 1; i < samples.size(); ++i) {
    if (!((samples[i] - samples[i - 1]).norm() > 0.0)) {
      throw InvalidArgument("initialShape", "resampled point " + std::to_string(i) + " = " + pointText(samples[i]),
                            "coincides with its predecessor (the shape folds back onto itself)");
    }
  }
  if (settings.variant == TractrixVariant::kPolyline) {
    KnotVector knots = polylineKnots(samples);
    return Initial{settings, std::move(knots), std::move(samples)};
  }
  // [B] §3.3 step 1: interpolate the vertices with a clamped spline of the chosen degree.
  Interpolation interpolation = interpolatePolyline(samples, settings.degree, Parametrization::kChordLength);
  const PointList& points = interpolation.curve.controlPoints();
  for (size_t i = 1; i < points.size(); ++i) {
    if (!((points[i] - points[i - 1]).norm() > 0.0)) {
      throw InvalidArgument("initialShape", "control point " + std::to_string(i) + " = " + pointText(points[i]),
                            "the interpolating control polygon has a zero-length side");
    }
  }
  return Initial{settings, interpolation.curve.knots(), points};
}

TractrixRope::TractrixRope(const PointList& initialShape, const TractrixSettings& settings)
    : TractrixRope(initialize(initialShape, settings)) {}

TractrixRope::TractrixRope(Initial initial)
    : settings_(initial.settings), knots_(std::move(initial.knots)), points_(std::move(initial.points)) {
  recomputeSides();
  initialLength_ = measureCurveLength();
  // Far below anything a merge should produce, far above rounding of the positions.
  minSide_ = 1e-9 * initialLength_;
  report_.controlPointCount = controlPointCount();
  report_.curveLength = initialLength_;
  report_.polygonLength = polygonLength(points_);
  report_.lengthError = 0.0;
}

void TractrixRope::recomputeSides() {
  sides_.resize(points_.size() - 1);
  for (size_t i = 0; i + 1 < points_.size(); ++i) sides_[i] = (points_[i + 1] - points_[i]).norm();
}

double TractrixRope::measureCurveLength() const {
  if (settings_.variant == TractrixVariant::kPolyline) return polygonLength(points_);
  ArcLengthOptions options;
  options.gaussPoints = settings_.lengthGaussPoints;
  options.piecesPerSpan = 1;
  return arcLength(knots_, points_, knots_.validBegin(), knots_.validEnd(), options);
}

const TractrixStepReport& TractrixRope::moveLeadingEnd(const Vec3& target) {
  for (int c = 0; c < 3; ++c) requireTractrixCoordinate("target[" + std::to_string(c) + "]", target[c]);

  report_.step += 1;
  report_.leadingDisplacement = (target - points_.front()).norm();
  report_.insertions = 0;
  report_.merges = 0;
  report_.reachedMaxControlPoints = false;
  report_.mergeRecords.clear();
  report_.correctionIterations = 0;

  double correctedLength = -1.0;  // the correction's own measurement of the curve, when it ran

  // [B] §3.3 step 3: the tractrix pass over the polygon keeps every side length.
  tractrixChainPass(points_, sides_, target);

  if (settings_.variant != TractrixVariant::kPolyline) {
    // Step 4: subdivide below the subdivision angle, then merge above the merging angle.
    report_.insertions = subdivideSharpCorners(knots_, points_, settings_.subdivisionAngle, minSide_,
                                               settings_.maxControlPoints);
    report_.reachedMaxControlPoints = controlPointCount() >= settings_.maxControlPoints;
    if (settings_.variant == TractrixVariant::kSplineSubdivideMerge) {
      MergeLimits limits;
      limits.mergingAngle = settings_.mergingAngle;
      limits.guardAngle = settings_.guardMerges ? settings_.subdivisionAngle : 0.0;
      limits.minSide = minSide_;
      limits.maxShapeError = settings_.maxMergeShapeError * initialLength_;
      limits.minControlPoints = settings_.effectiveMinControlPoints();
      report_.merges = mergeStraightCorners(knots_, points_, limits, report_.mergeRecords);
    }
    bool changed = report_.insertions > 0 || report_.merges > 0;
    if (settings_.lengthCorrection == TractrixLengthCorrection::kRestoreCurveLength) {
      // Beyond [B]: re-lay the polygon so that the curve keeps its initial length (length_correction.h),
      // measured with the same quadrature as the reported curve length.
      LengthCorrectionOptions options;
      options.gaussPoints = settings_.lengthGaussPoints;
      const LengthCorrectionResult correction =
          restoreCurveLength(knots_, points_, initialLength_, options, correctionWorkspace_);
      correctedLength = correction.lengthAfter;
      report_.lengthErrorBeforeCorrection = (correction.lengthBefore - initialLength_) / initialLength_;
      report_.correctionIterations = correction.iterations;
      if (!correction.feasible) ++report_.correctionFailures;
      changed = changed || correction.applied;
    }
    // Insertion, removal and the correction change the polygon: the new sides are the lengths the
    // pass keeps next.
    if (changed) recomputeSides();
  }

  report_.controlPointCount = controlPointCount();
  report_.curveLength = correctedLength >= 0.0 ? correctedLength : measureCurveLength();
  report_.polygonLength = polygonLength(points_);
  report_.lengthError = (report_.curveLength - initialLength_) / initialLength_;
  if (settings_.lengthCorrection != TractrixLengthCorrection::kRestoreCurveLength ||
      settings_.variant == TractrixVariant::kPolyline) {
    report_.lengthErrorBeforeCorrection = report_.lengthError;
  }
  return report_;
}

void TractrixRope::sampleCurve(int count, PointList& out) const {
  if (count < 2) throw InvalidArgument("count", std::to_string(count), "must be >= 2");
  out.resize(static_cast<size_t>(count));
  const double begin = knots_.validBegin();
  const double end = knots_.validEnd();
  for (int j = 0; j < count; ++j) {
    const double s = j + 1 == count ? end : begin + (end - begin) * j / (count - 1);
    out[static_cast<size_t>(j)] = curvePosition(knots_, points_, s);
  }
}

}  // namespace rope
