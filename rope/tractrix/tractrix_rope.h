// SPDX-License-Identifier: MIT
#pragma once
// A kinematic rope driven by its leading end ([B] §3.3): the tractrix chain pass moves the control
// polygon (or, for TRX, the polyline itself), then the polygon is adapted by angle thresholds ([B]),
// and finally (by default, beyond [B]) re-laid so that the curve keeps its initial length
// (length_correction.h). Purely geometric: no mass, no time step.
//
// The leading end is control point 0 (the curve is clamped, so it is also the curve's end C(begin)).
// A driver — a scripted path, or a rigid body's point in a physics engine — calls moveLeadingEnd()
// once per step with the new position and reads back the curve (knots(), controlPoints(), curve(),
// sampleCurve()). Each call treats the move as a straight line from the old position.
//
// Settings (what the user configures) are fixed at construction; the state (knots, points, side
// lengths) changes each step.

#include <vector>

#include "rope/common/types.h"
#include "rope/spline/bspline_curve.h"
#include "rope/spline/knot_vector.h"
#include "rope/tractrix/length_correction.h"
#include "rope/tractrix/polygon_adaptation.h"
#include "rope/tractrix/tractrix_settings.h"

namespace rope {

// What one step did and where it left the rope. Lengths in metres.
struct TractrixStepReport {
  long step = 0;                   // number of moveLeadingEnd() calls so far (0: initial state)
  double leadingDisplacement = 0;  // |target - previous leading end|
  int controlPointCount = 0;       // after adaptation (TRX: segmentCount + 1)
  int insertions = 0;              // subdivisions in this step
  int merges = 0;                  // merges in this step
  bool reachedMaxControlPoints = false;  // subdivision stopped at settings.maxControlPoints
  double curveLength = 0.0;        // arc length of the curve after the step (TRX: polyline length)
  double polygonLength = 0.0;      // length of the control polygon (TRX: the same polyline)
  double lengthError = 0.0;        // (curveLength - initialLength) / initialLength, signed
  // The same error after the pass and the adaptation, before settings.lengthCorrection re-laid the
  // polygon (equal to lengthError when there is no correction).
  double lengthErrorBeforeCorrection = 0.0;
  int correctionIterations = 0;    // Newton iterations of the length correction in this step
  // Steps so far in which the length correction found no admissible polygon (it would have shrunk a
  // side to less than half, or did not converge) and left the polygon uncorrected. A warning count:
  // the next step corrects again from wherever this one left the curve.
  long correctionFailures = 0;
  std::vector<MergeRecord> mergeRecords;  // one per merge in this step, with its own error
};

class TractrixRope {
 public:
  // Lays the rope along initialShape (>= 2 points, coordinates finite and within
  // kMaxTractrixCoordinate, consecutive points distinct), leading end
  // first. The shape is resampled at segmentCount + 1 points equally spaced in arc length; TRX uses
  // them as its polyline, the spline variants interpolate them with a clamped B-spline of
  // settings.degree ([B] §3.3 step 1; chord-length parameters, so s is close to arc length).
  // Throws InvalidArgument for bad settings ("settings.<field>") or shape ("initialShape...").
  explicit TractrixRope(const PointList& initialShape, const TractrixSettings& settings = {});

  // One step: moves the leading end to target (straight-line move), runs the tractrix chain pass,
  // then (spline variants) subdivides, merges and corrects the length (settings.lengthCorrection).
  // Throws InvalidArgument("target[c]", ...) for a coordinate that is not finite or beyond
  // kMaxTractrixCoordinate, leaving the rope unchanged.
  // The report stays valid until the next call.
  const TractrixStepReport& moveLeadingEnd(const Vec3& target);

  const TractrixSettings& settings() const { return settings_; }
  const TractrixStepReport& lastReport() const { return report_; }

  // The curve: degree settings.degree for the spline variants, degree 1 (the polyline) for TRX.
  const KnotVector& knots() const { return knots_; }
  const PointList& controlPoints() const { return points_; }
  int degree() const { return knots_.degree(); }
  int controlPointCount() const { return static_cast<int>(points_.size()); }
  // Rest lengths of the polygon sides that the tractrix pass keeps (metres).
  const std::vector<double>& sideLengths() const { return sides_; }
  BSplineCurve curve() const { return BSplineCurve(knots_, points_); }

  const Vec3& leadingEnd() const { return points_.front(); }
  const Vec3& trailingEnd() const { return points_.back(); }
  double initialLength() const { return initialLength_; }  // curve length right after construction
  double curveLength() const { return report_.curveLength; }
  double lengthError() const { return report_.lengthError; }

  // count >= 2 points of the curve at equally spaced parameters, leading end first ("count").
  void sampleCurve(int count, PointList& out) const;

 private:
  struct Initial;
  explicit TractrixRope(Initial initial);
  static Initial initialize(const PointList& shape, const TractrixSettings& settings);
  double measureCurveLength() const;
  void recomputeSides();

  TractrixSettings settings_;
  KnotVector knots_;
  PointList points_;
  std::vector<double> sides_;
  double initialLength_ = 0.0;
  double minSide_ = 0.0;  // merges may not create a side shorter than this (metres)
  TractrixStepReport report_;
  LengthCorrectionWorkspace correctionWorkspace_;  // scratch, no state
};

}  // namespace rope
