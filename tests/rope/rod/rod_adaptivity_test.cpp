// SPDX-License-Identifier: MIT
// Adaptivity after each step ([A] §4; docs/method.md §10).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "rope/rod/adaptivity.h"
#include "rope/rod/rod.h"
#include "rope/spline/knot_removal.h"
#include "tests/rope/rod/rod_test_util.h"

namespace rope {
namespace {

TEST(Adaptivity, CurvatureInsertionSpansFollowTheBentCorners) {
  const KnotVector knots = KnotVector::clampedUniform(3, 8, 0.0, 5.0);
  PointList points;
  for (int i = 0; i < 8; ++i) points.emplace_back(i, 0, 0);
  points[4] = Vec3(4, 1.5, 0);  // one sharp corner
  std::vector<double> bend;
  bendMeasures(points, bend);
  EXPECT_EQ(bend[0], 0.0);
  EXPECT_GT(bend[4], 0.5);
  EXPECT_EQ(bend[1], 0.0);
  std::vector<int> spans;
  curvatureInsertionSpans(knots, bend, 0.117, spans);
  // The sides q2q3, q3q4, q4q5, q5q6 touch bent corners; their middles lie in spans around the
  // Greville abscissae of q3..q5.
  ASSERT_FALSE(spans.empty());
  for (int k : spans) {
    EXPECT_GE(knots[k + 1], grevilleAbscissa(knots, 2));
    EXPECT_LE(knots[k], grevilleAbscissa(knots, 6));
  }
  EXPECT_TRUE(std::is_sorted(spans.begin(), spans.end()));
}

TEST(Adaptivity, LocalRemovalErrorIsZeroForARedundantKnot) {
  KnotVector knots = KnotVector::clampedUniform(3, 9, 0.0, 1.0);
  PointList points;
  for (int i = 0; i < 9; ++i) points.emplace_back(std::cos(0.3 * i), std::sin(0.3 * i), 0.1 * i);
  const double s = 0.4321;
  insertKnot(knots, points, s);
  const KnotRemoval plan = planKnotRemoval(knots, points, s);
  EXPECT_LT(localRemoval(plan, points).error, 1e-13);
  points[6] += Vec3(0.1, 0, 0);  // now the knot is needed
  const KnotRemoval needed = planKnotRemoval(knots, points, s);
  EXPECT_GT(localRemoval(needed, points).error, 1e-3);
  EXPECT_NEAR(localRemoval(needed, points).error, needed.chosenShapeError(), 1e-12);
}

// A rope draped over a peg (pinned at its middle) folds tightly there: it must gain control points
// only near the fold; once it hangs straight from one end it loses them again.
// [A]/[B]'s criterion: RemovalCriterion::kMechanicalOutOfContact (the default) keeps about three
// times as many on the pulled, sagging rope, which is loaded (tension and its own weight), not
// straight and still.
TEST(Adaptivity, TightFoldGainsPointsOnlyNearTheFoldAndLosesThemWhenStraight) {
  RodSettings settings;
  settings.removalCriterion = RemovalCriterion::kPolygon;
  settings.restLength = 1.0;
  settings.linearDensity = 0.05;
  settings.youngsModulus = 1e8;
  settings.radius = 0.002;
  settings.bendingStiffness = 1e-4;  // fold radius ~ sqrt(EI / T) ~ a few cm
  settings.massDamping = 3.0;
  settings.initialControlPoints = 12;
  settings.minControlPoints = 8;
  settings.maxControlPoints = 40;
  Rod rod = Rod::fromSegment(settings, Vec3(-0.5, 0, 0), Vec3(0.5, 0, 0));
  const std::vector<double> initialKnots = rod.knots().values();
  const int peg = rod.pin(0.5);
  int maxCount = 0, insertions = 0;
  for (int i = 0; i < 240 * 6; ++i) {
    const StepReport report = rod.step(1.0 / 240);
    ASSERT_TRUE(report.ok) << report.failure;
    EXPECT_GE(report.controlPoints, settings.minControlPoints);
    EXPECT_LE(report.controlPoints, settings.maxControlPoints);
    maxCount = std::max(maxCount, report.controlPoints);
    insertions += report.insertions;
  }
  // Folded: both halves hang down.
  EXPECT_LT(rod.position(0.0).y(), -0.4);
  EXPECT_LT(rod.position(1.0).y(), -0.4);
  const int foldedCount = rod.controlPointCount();
  EXPECT_GT(foldedCount, 12);
  // Every knot that was not there at the start lies near the fold (|s - 0.5| < 0.2).
  int added = 0;
  for (double t : rod.knots().values()) {
    if (std::find(initialKnots.begin(), initialKnots.end(), t) != initialKnots.end()) continue;
    ++added;
    EXPECT_LT(std::abs(t - 0.5), 0.2) << "added knot at " << t;
  }
  EXPECT_GE(added, 2);
  // Straighten: take both ends and pull them apart until the rope is taut and horizontal.
  // (Releasing the peg and letting the rope hang from one end is not used: the falling half whips
  // into a small loop, which in an exactly planar simulation can never come out.)
  const Vec3 leftStart = rod.position(0.0);
  const Vec3 rightStart = rod.position(1.0);
  const int leftEnd = rod.pin(0.0);
  const int rightEnd = rod.pin(1.0);
  rod.releasePin(peg);
  const Vec3 leftGoal(-0.502, 0.0, 0.0);
  const Vec3 rightGoal(0.502, 0.0, 0.0);
  int removals = 0;
  for (int i = 0; i < 240 * 8; ++i) {
    const double u = std::min(1.0, (i + 1) / (240.0 * 4));
    rod.setPinTarget(leftEnd, (1.0 - u) * leftStart + u * leftGoal);
    rod.setPinTarget(rightEnd, (1.0 - u) * rightStart + u * rightGoal);
    const StepReport report = rod.step(1.0 / 240);
    ASSERT_TRUE(report.ok) << report.failure;
    EXPECT_GE(report.controlPoints, settings.minControlPoints);
    EXPECT_LE(report.controlPoints, settings.maxControlPoints);
    removals += report.removals;
    EXPECT_LE(report.maxRemovalError, settings.removalErrorBound);
  }
  EXPECT_GT(test::lowestY(rod), -0.02);  // taut and nearly straight
  EXPECT_LE(rod.controlPointCount(), 12);
  EXPECT_GT(removals, 0);
  std::printf("[fold] initial 12, folded %d (max %d, %d insertions), straightened %d (%d removals)\n", foldedCount,
              maxCount, insertions, rod.controlPointCount(), removals);
}

TEST(Adaptivity, CountsStayWithinTheLimits) {
  RodSettings settings;
  settings.restLength = 1.0;
  settings.linearDensity = 0.05;
  settings.youngsModulus = 1e8;
  settings.bendingStiffness = 0.0;
  settings.initialControlPoints = 6;
  settings.minControlPoints = 5;
  settings.maxControlPoints = 9;
  // Violently slack, lots of bending: 1 m of rope between pins 0.5 m apart. (It was pulled there by
  // moving one pin 0.8 m in one step, and then to 0.2 m: from step 2 on, the linearised step made the
  // rope over three times its rest length, which Rod::kMaxStepStretch now refuses; measured here: up
  // to 2.7 times, counts 6 to 9.)
  Rod rod = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(0.5, 0, 0));
  rod.pin(0.0);
  rod.pin(1.0);
  for (int i = 0; i < 600; ++i) {
    const StepReport report = rod.step(1.0 / 240);
    ASSERT_TRUE(report.ok);
    ASSERT_GE(report.controlPoints, 5);
    ASSERT_LE(report.controlPoints, 9);
  }
}

}  // namespace
}  // namespace rope

namespace rope {
namespace {

// Adaptive removal respects the velocity bound: a straight rope whose velocity field the coarser
// spline cannot carry keeps its knots, and once the field is one the coarse spline holds (a
// uniform velocity) the same knots go.
TEST(Adaptivity, RemovalWaitsForAVelocityFieldTheCoarserSplineCanCarry) {
  RodSettings settings;
  settings.gravity = Vec3::Zero();
  settings.initialControlPoints = 16;
  settings.minControlPoints = 4;
  Rod rod = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(1, 0, 0));
  const int count = rod.controlPointCount();
  const PointList straight = rod.controlPoints();
  PointList wavy(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) wavy[static_cast<size_t>(i)] = Vec3(0, 0, (i % 2 == 0 ? 0.5 : -0.5));
  rod.setVelocities(wavy);
  const StepReport blocked = rod.step(1e-6);
  ASSERT_TRUE(blocked.ok);
  EXPECT_EQ(blocked.removals, 0);
  EXPECT_EQ(rod.controlPointCount(), count);

  // The wavy step left a 5e-7 m zigzag in the shape, which RemovalCriterion::kMechanical rightly
  // keeps (it is not representable on fewer knots); this test is about the velocity field.
  rod.setControlPoints(straight);
  rod.setVelocities(PointList(static_cast<size_t>(count), Vec3(0, 0, 0.5)));
  const Vec3 momentum = rod.momentum();
  const StepReport allowed = rod.step(1e-6);
  ASSERT_TRUE(allowed.ok);
  EXPECT_GT(allowed.removals, 0);
  EXPECT_LE(allowed.maxRemovalVelocityError, settings.removalVelocityErrorBound);
  EXPECT_LT((rod.momentum() - momentum).norm(), rod.mass() * settings.removalVelocityErrorBound);
}

}  // namespace
}  // namespace rope

namespace rope {
namespace {

// A straight, still, weightless rope of 16 control points with a 2 um zigzag (far under
// removalErrorBound, a polygon the removal threshold calls straight), in contact (kPolygon removal):
// each removal moves its curve by a small, non-zero shape error.
Rod zigzagRopeInContact() {
  RodSettings settings;
  settings.gravity = Vec3::Zero();
  settings.initialControlPoints = 16;
  settings.minControlPoints = 4;
  Rod rod = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(1, 0, 0));
  PointList points = rod.controlPoints();
  for (size_t i = 0; i < points.size(); ++i) points[i].y() += (i % 2 == 0 ? 1e-6 : -1e-6);
  rod.setControlPoints(points);
  rod.markContact();
  return rod;
}

// Rod::limitShapeChange caps the removals of the coming commit near s (a contact whose friction holds
// a load, docs/method.md §10), only there, and only for that commit.
TEST(Adaptivity, LimitShapeChangeKeepsTheKnotsNearTheCappedPointsForOneCommit) {
  Rod free = zigzagRopeInContact();
  const StepReport unlimited = free.step(1e-6);
  ASSERT_TRUE(unlimited.ok);
  ASSERT_GT(unlimited.removals, 0);
  ASSERT_GT(unlimited.maxRemovalError, 0.0);

  // Capped to 0 over the first half: no removal changes the curve there; the second half coarsens.
  Rod capped = zigzagRopeInContact();
  const std::vector<double> knotsBefore = capped.knots().values();
  for (int i = 0; i <= 50; ++i) capped.limitShapeChange(0.01 * i, 0.0);
  const StepReport report = capped.step(1e-6);
  ASSERT_TRUE(report.ok);
  EXPECT_GT(report.removals, 0);
  EXPECT_LT(report.removals, unlimited.removals);
  const std::vector<double> knotsAfter = capped.knots().values();
  for (double knot : knotsBefore) {
    if (knot > 0.5) continue;
    EXPECT_NE(std::find(knotsAfter.begin(), knotsAfter.end(), knot), knotsAfter.end()) << "knot " << knot << " removed";
  }

  // A cap the removals stay within changes nothing (bitwise the same as no cap).
  Rod loose = zigzagRopeInContact();
  for (int i = 0; i <= 100; ++i) loose.limitShapeChange(0.01 * i, 1.0);
  ASSERT_TRUE(loose.step(1e-6).ok);
  EXPECT_TRUE(test::sameState(test::RodSnapshot(free), test::RodSnapshot(loose)));

  // The caps were for that commit only: the next one coarsens the first half too.
  capped.markContact();
  const StepReport next = capped.step(1e-6);
  ASSERT_TRUE(next.ok);
  EXPECT_GT(next.removals, 0);
}

TEST(Adaptivity, LimitShapeChangeRejectsBadInputNamingTheParameter) {
  Rod rod = zigzagRopeInContact();
  const double nan = std::nan("");
  test::expectEachCallRejected(rod, {
                                        {"s", [](Rod& r) { r.limitShapeChange(-0.1, 1e-6); }},
                                        {"s", [](Rod& r) { r.limitShapeChange(1.5, 1e-6); }},
                                        {"s", [nan](Rod& r) { r.limitShapeChange(nan, 1e-6); }},
                                        {"maxChange", [](Rod& r) { r.limitShapeChange(0.5, -1e-9); }},
                                        {"maxChange", [nan](Rod& r) { r.limitShapeChange(0.5, nan); }},
                                        {"maxChange", [](Rod& r) { r.limitShapeChange(0.5, INFINITY); }},
                                    });
  // Nothing was queued: the step is bitwise a step without the calls.
  Rod twin = zigzagRopeInContact();
  ASSERT_TRUE(rod.step(1e-6).ok);
  ASSERT_TRUE(twin.step(1e-6).ok);
  EXPECT_TRUE(test::sameState(test::RodSnapshot(twin), test::RodSnapshot(rod)));
}

}  // namespace
}  // namespace rope
