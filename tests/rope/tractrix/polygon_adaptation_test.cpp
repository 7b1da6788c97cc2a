// SPDX-License-Identifier: MIT
// Subdivision leaves the curve unchanged and opens every corner; merging reports its own error,
// picks the candidate with the smaller length error, and respects the guard and the floor.
#include "rope/tractrix/polygon_adaptation.h"

#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>

#include "rope/spline/arc_length.h"
#include "rope/spline/bspline_curve.h"
#include "rope/spline/control_polygon.h"
#include "rope/spline/knot_insertion.h"
#include "rope/tractrix/tractrix_settings.h"

namespace rope {
namespace {

double smallestCorner(const PointList& points) {
  double smallest = kTractrixPi;
  for (int i = 1; i + 1 < static_cast<int>(points.size()); ++i) smallest = std::min(smallest, includedAngle(points, i));
  return smallest;
}

MergeLimits limits(double mergingDegrees, double guardDegrees, int minControlPoints) {
  MergeLimits result;
  result.mergingAngle = degrees(mergingDegrees);
  result.guardAngle = degrees(guardDegrees);
  result.minSide = 1e-9;
  result.maxShapeError = 1.0;
  result.minControlPoints = minControlPoints;
  return result;
}

double fullLength(const KnotVector& knots, const PointList& points) {
  ArcLengthOptions options;
  options.gaussPoints = 24;
  return arcLength(knots, points, knots.validBegin(), knots.validEnd(), options);
}

// A clamped cubic whose polygon turns by `turnDegrees` at each interior corner, unit sides.
void bentPolygon(int count, double turnDegrees, KnotVector& knots, PointList& points) {
  knots = KnotVector::clampedUniform(3, count, 0.0, count - 3.0);
  points.clear();
  Vec3 p = Vec3::Zero();
  double heading = 0.0;
  for (int i = 0; i < count; ++i) {
    points.push_back(p);
    p += Vec3(std::cos(heading), std::sin(heading), 0.0);
    heading += degrees(turnDegrees);
  }
}

TEST(PolygonAdaptation, SubdivisionKeepsTheCurveAndOpensEveryCorner) {
  KnotVector knots = KnotVector::clampedUniform(3, 4);
  PointList points;
  bentPolygon(8, 70.0, knots, points);  // included angles of 110°
  const KnotVector knotsBefore = knots;
  const PointList pointsBefore = points;
  const double polygonBefore = polygonLength(points);
  const int inserted = subdivideSharpCorners(knots, points, degrees(140.0), 1e-9, 1000);
  EXPECT_GT(inserted, 0);
  EXPECT_EQ(static_cast<int>(points.size()), 8 + inserted);
  EXPECT_GE(smallestCorner(points), degrees(140.0));
  // [B] §3.1: the polygon gets shorter, the curve does not change at all (exact insertion).
  EXPECT_LT(polygonLength(points), polygonBefore);
  for (int j = 0; j <= 200; ++j) {
    const double s = knotsBefore.validBegin() + (knotsBefore.validEnd() - knotsBefore.validBegin()) * j / 200.0;
    EXPECT_LT((curvePosition(knots, points, s) - curvePosition(knotsBefore, pointsBefore, s)).norm(), 1e-12);
  }
}

TEST(PolygonAdaptation, SubdivisionStopsAtTheMaximumCount) {
  KnotVector knots = KnotVector::clampedUniform(3, 4);
  PointList points;
  bentPolygon(8, 80.0, knots, points);
  EXPECT_EQ(subdivideSharpCorners(knots, points, degrees(175.0), 1e-9, 11), 3);
  EXPECT_EQ(points.size(), 11u);
  EXPECT_EQ(knots.controlPointCount(), 11);
  // Already at the cap: nothing happens.
  EXPECT_EQ(subdivideSharpCorners(knots, points, degrees(175.0), 1e-9, 11), 0);
}

TEST(PolygonAdaptation, StraightPolygonIsLeftAlone) {
  KnotVector knots = KnotVector::clampedUniform(3, 4);
  PointList points;
  bentPolygon(9, 0.0, knots, points);
  const PointList before = points;
  EXPECT_EQ(subdivideSharpCorners(knots, points, degrees(170.0), 1e-9, 100), 0);
  EXPECT_EQ(points, before);
}

TEST(PolygonAdaptation, MergingUndoesRefinementOfAStraightishCurveAndReportsItsError) {
  // A gently bent curve refined far beyond need: merging brings it back down, each merge's
  // reported length error matching the change of the whole curve's length.
  KnotVector knots = KnotVector::clampedUniform(3, 4);
  PointList points;
  bentPolygon(7, 12.0, knots, points);
  for (int round = 0; round < 3; ++round) {
    const std::vector<double> values = knots.values();
    for (size_t i = 3; i + 4 < values.size(); ++i) insertKnot(knots, points, 0.5 * (values[i] + values[i + 1]));
  }
  const int refined = static_cast<int>(points.size());
  ASSERT_GT(refined, 20);
  std::vector<MergeRecord> records;
  int merges = 0;
  // One merge at a time, so that each record can be checked against the whole curve's change.
  for (;;) {
    const double lengthBefore = fullLength(knots, points);
    const size_t recordsBefore = records.size();
    const int merged =
        mergeStraightCorners(knots, points, limits(160.0, 140.0, static_cast<int>(points.size()) - 1), records);
    if (merged == 0) break;
    ASSERT_EQ(merged, 1);
    ASSERT_EQ(records.size(), recordsBefore + 1);
    ++merges;
    const MergeRecord& record = records.back();
    // The chosen candidate is the one with the smaller length error ([B] §3.2).
    EXPECT_LE(record.chosenLengthError(), record.lengthError[1 - record.chosen]);
    EXPECT_GE(record.chosenLengthError(), 0.0);
    EXPECT_GE(record.chosenShapeError(), 0.0);
    EXPECT_NEAR(std::fabs(fullLength(knots, points) - lengthBefore), record.chosenLengthError(), 1e-9);
  }
  EXPECT_GT(merges, 5);
  EXPECT_EQ(static_cast<int>(points.size()), refined - merges);
  EXPECT_EQ(knots.controlPointCount(), static_cast<int>(points.size()));
  EXPECT_GE(smallestCorner(points), degrees(140.0));  // the guard held
}

TEST(PolygonAdaptation, MergingRespectsTheFloorAndTheThreshold) {
  KnotVector knots = KnotVector::clampedUniform(3, 4);
  PointList points;
  bentPolygon(12, 0.0, knots, points);  // straight: every knot is removable exactly
  std::vector<MergeRecord> records;
  EXPECT_EQ(mergeStraightCorners(knots, points, limits(160.0, 140.0, 9), records), 3);
  EXPECT_EQ(points.size(), 9u);
  for (const MergeRecord& record : records) EXPECT_LT(record.chosenLengthError(), 1e-12);
  // Corners at 150° are below the merging angle: nothing to merge.
  bentPolygon(9, 30.0, knots, points);
  records.clear();
  EXPECT_EQ(mergeStraightCorners(knots, points, limits(160.0, 140.0, 4), records), 0);
  EXPECT_TRUE(records.empty());
}

TEST(PolygonAdaptation, MergingRespectsTheShapeErrorLimit) {
  // Corners of 165° are mergeable, but no removal is exact there: with a tiny shape limit every
  // candidate is rejected, with a generous one merges happen and stay within it.
  KnotVector knots = KnotVector::clampedUniform(3, 4);
  PointList points;
  bentPolygon(10, 15.0, knots, points);
  std::vector<MergeRecord> records;
  MergeLimits tight = limits(160.0, 0.0, 4);
  tight.maxShapeError = 1e-6;
  const PointList before = points;
  EXPECT_EQ(mergeStraightCorners(knots, points, tight, records), 0);
  EXPECT_EQ(points, before);
  MergeLimits loose = limits(160.0, 0.0, 4);
  loose.maxShapeError = 0.2;
  EXPECT_GT(mergeStraightCorners(knots, points, loose, records), 0);
  for (const MergeRecord& record : records) {
    EXPECT_GT(record.chosenShapeError(), 1e-6);
    EXPECT_LE(record.chosenShapeError(), 0.2);
  }
}

}  // namespace
}  // namespace rope
