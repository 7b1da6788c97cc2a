// SPDX-License-Identifier: MIT
#include "rope/spline/knot_removal.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "rope/common/fixed_vector.h"
#include "rope/spline/arc_length.h"
#include "rope/spline/bspline_curve.h"
#include "rope/spline/knot_insertion.h"
#include "tests/rope/spline/spline_test_support.h"

namespace rope {
namespace {

using test::expectInvalid;

// Interior knot values (strictly inside the valid range), one entry per distinct value.
std::vector<double> interiorKnots(const KnotVector& knots) {
  std::vector<double> values;
  for (double t : knots.values()) {
    if (t > knots.validBegin() && t < knots.validEnd() && (values.empty() || values.back() != t)) {
      values.push_back(t);
    }
  }
  return values;
}

double maxPointDistance(const PointList& a, const PointList& b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
  return worst;
}

// The candidate of one side built independently of the plan's own error computation: apply the
// sweep to a copy of the points and drop the knot.
BSplineCurve candidate(const BSplineCurve& curve, const KnotRemoval& removal, KnotRemoval::Side side) {
  PointList points = curve.controlPoints();
  removal.apply(points, side);
  KnotVector knots = curve.knots();
  knots.eraseAt(removal.knotIndex);
  return BSplineCurve(knots, points);
}

TEST(KnotRemoval, InsertThenRemoveRestoresTheControlPoints) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0.0;
  double worstReported = 0.0;
  double worstUnchosen = 0.0;
  for (int trial = 0; trial < 1000; ++trial) {
    const int degree = 1 + trial % kMaxDegree;
    const BSplineCurve original = test::randomCurve(rng, degree, trial % 2 == 0, degree);
    BSplineCurve curve = original;
    double s = original.beginParameter() + (original.endParameter() - original.beginParameter()) * unit(rng);
    const std::vector<double> interior = interiorKnots(original.knots());
    // Every third trial re-inserts an existing knot, raising its multiplicity.
    if (trial % 3 == 0 && !interior.empty()) {
      const double t = interior[static_cast<size_t>(trial) % interior.size()];
      if (original.knots().multiplicity(t) <= degree) s = t;
    }
    if (!(s > original.beginParameter() && s < original.endParameter())) continue;
    curve.insertKnot(s);
    const KnotRemoval removal = curve.removeKnot(s);
    const double size = test::sizeOf(original.controlPoints());
    ASSERT_EQ(curve.knots().values(), original.knots().values());
    ASSERT_EQ(curve.controlPointCount(), original.controlPointCount());
    worst = std::max(worst, maxPointDistance(curve.controlPoints(), original.controlPoints()) / size);
    // Both sweeps are exact in exact arithmetic; in floating point a sweep divides by its a_i (left)
    // or 1 - a_i (right) and can amplify rounding, so only the chosen side must be at rounding level.
    worstReported = std::max({worstReported, removal.chosenShapeError() / size});
    EXPECT_LE(removal.chosenLengthError(), 1e-12 * arcLength(original));
    worstUnchosen = std::max(worstUnchosen, removal.shapeError[1 - removal.chosen] / size);
  }
  std::printf("insert+remove: max |q - q_original| / size %.3g, chosen side's shape error / size %.3g "
              "(other side up to %.3g)\n",
              worst, worstReported, worstUnchosen);
  EXPECT_LE(worst, 1e-12);
  EXPECT_LE(worstReported, 1e-12);
}

TEST(KnotRemoval, ErrorsOfBothCandidatesMatchIndependentComputation) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int checked = 0;
  int rightChosen = 0;
  double worstShapeMismatch = 0.0;
  double worstLengthMismatch = 0.0;
  double worstBoundExcess = -1.0;
  double largestSmoothLengthError = 0.0;
  const ArcLengthOptions fine{24, 8};  // a finer rule than the library's default, for independence
  for (int trial = 0; trial < 300; ++trial) {
    const int degree = 1 + trial % kMaxDegree;
    // Rope-like curves (small removal errors) and wild random ones (large errors, where the
    // candidates can fold back so sharply that quadrature of |C'| loses digits: no length check).
    const bool smooth = (trial / kMaxDegree) % 2 == 0;
    const BSplineCurve curve = smooth ? test::smoothCurve(rng, degree, trial % 2 == 1)
                                      : test::randomCurve(rng, degree, trial % 2 == 1, degree);
    const std::vector<double> interior = interiorKnots(curve.knots());
    if (interior.empty() || curve.controlPointCount() <= degree + 1) continue;
    const double s = interior[static_cast<size_t>(unit(rng) * static_cast<double>(interior.size())) % interior.size()];
    const KnotRemoval removal = planKnotRemoval(curve.knots(), curve.controlPoints(), s);
    const double size = test::sizeOf(curve.controlPoints());
    const double length = arcLength(curve, fine);
    // A random curve has no spare freedom: removal must report a real error on both sides.
    EXPECT_GT(removal.shapeError[0], 0.0);
    EXPECT_GT(removal.shapeError[1], 0.0);
    for (int side = 0; side < 2; ++side) {
      const BSplineCurve piece = candidate(curve, removal, static_cast<KnotRemoval::Side>(side));
      // shapeError: re-insert the knot into the candidate and compare control points.
      BSplineCurve reinserted = piece;
      reinserted.insertKnot(s);
      ASSERT_EQ(reinserted.knots().values(), curve.knots().values());
      const double shape = maxPointDistance(reinserted.controlPoints(), curve.controlPoints());
      worstShapeMismatch = std::max(worstShapeMismatch, std::fabs(shape - removal.shapeError[static_cast<size_t>(side)]) / size);
      // lengthError: whole-curve arc lengths (the curves agree outside the affected range).
      const double lengthChange = std::fabs(arcLength(piece, fine) - length);
      if (smooth) {
        worstLengthMismatch = std::max(worstLengthMismatch,
                                       std::fabs(lengthChange - removal.lengthError[static_cast<size_t>(side)]) / length);
        largestSmoothLengthError = std::max(largestSmoothLengthError, removal.lengthError[static_cast<size_t>(side)] / length);
      }
      // shapeError bounds the displacement of the curve, checked on dense samples.
      double displacement = 0.0;
      for (int i = 0; i <= 2000; ++i) {
        const double t = std::min(curve.endParameter(),
                                  curve.beginParameter() + (curve.endParameter() - curve.beginParameter()) * i / 2000.0);
        displacement = std::max(displacement, (piece.position(t) - curve.position(t)).norm());
      }
      worstBoundExcess = std::max(worstBoundExcess, (displacement - removal.shapeError[static_cast<size_t>(side)]) / size);
    }
    // The chosen side has the smaller length error (ties go left).
    const KnotRemoval::Side expected =
        removal.lengthError[1] < removal.lengthError[0] ? KnotRemoval::kFromRight : KnotRemoval::kFromLeft;
    EXPECT_EQ(removal.chosen, expected);
    EXPECT_EQ(removal.chosenLengthError(), std::min(removal.lengthError[0], removal.lengthError[1]));
    rightChosen += removal.chosen == KnotRemoval::kFromRight ? 1 : 0;
    // removeKnot applies exactly that candidate.
    BSplineCurve removed = curve;
    removed.removeKnot(s);
    EXPECT_EQ(removed.controlPoints(), candidate(curve, removal, removal.chosen).controlPoints());
    ++checked;
  }
  std::printf("removal candidates checked %d (right chosen %d): shape mismatch %.3g, length mismatch %.3g "
              "(relative; rope-like curves, errors up to %.3g of the length), max (displacement - shapeError)/size %.3g\n",
              checked, rightChosen, worstShapeMismatch, worstLengthMismatch, largestSmoothLengthError, worstBoundExcess);
  EXPECT_GT(checked, 200);
  EXPECT_GT(rightChosen, 0);  // both sides really occur
  EXPECT_LT(rightChosen, checked);
  EXPECT_LE(worstShapeMismatch, 1e-12);
  EXPECT_LE(worstLengthMismatch, 1e-9);
  EXPECT_LE(worstBoundExcess, 1e-12);
}

TEST(KnotRemoval, RemovesFromAKnotOfMultiplicityDegreeAndDegreePlusOne) {
  // Quadratic with the interior knot 1 at multiplicity 2 (= d: C^0 corner) and 3 (= d+1: a cut).
  for (int m : {2, 3}) {
    std::vector<double> t{0, 0, 0};
    for (int i = 0; i < m; ++i) t.push_back(1.0);
    t.insert(t.end(), {2, 2, 2});
    const KnotVector knots(2, t);
    PointList points;
    for (int i = 0; i < knots.controlPointCount(); ++i) points.push_back(Vec3(i, i * i % 3, 0.5 * i));
    BSplineCurve curve(knots, points);
    const BSplineCurve before = curve;
    const KnotRemoval removal = curve.removeKnot(1.0);
    EXPECT_EQ(removal.multiplicityAfter, m - 1);
    EXPECT_EQ(curve.knots().multiplicity(1.0), m - 1);
    EXPECT_EQ(curve.controlPointCount(), before.controlPointCount() - 1);
    EXPECT_GT(removal.chosenShapeError(), 0.0);
    // The re-inserted candidate differs from the original by exactly the reported shape error.
    BSplineCurve reinserted = curve;
    reinserted.insertKnot(1.0);
    EXPECT_NEAR(maxPointDistance(reinserted.controlPoints(), before.controlPoints()), removal.chosenShapeError(), 1e-14);
  }
}

TEST(KnotRemoval, VelocitiesFollowTheSameLinearMap) {
  // apply() is linear: removing from a*x + y gives a*removed(x) + removed(y).
  std::mt19937 rng(17);
  const BSplineCurve curve = test::randomCurve(rng, 3, true, 1);
  const std::vector<double> interior = interiorKnots(curve.knots());
  ASSERT_FALSE(interior.empty());
  const KnotRemoval removal = planKnotRemoval(curve.knots(), curve.controlPoints(), interior.front());
  PointList x = curve.controlPoints();
  PointList y(x.size());
  for (size_t i = 0; i < y.size(); ++i) y[i] = Vec3(std::sin(1.0 + i), std::cos(2.0 * i), 0.1 * i);
  PointList combined(x.size());
  for (size_t i = 0; i < x.size(); ++i) combined[i] = 2.5 * x[i] + y[i];
  removal.apply(x);
  removal.apply(y);
  removal.apply(combined);
  for (size_t i = 0; i < x.size(); ++i) EXPECT_LE((combined[i] - (2.5 * x[i] + y[i])).norm(), 1e-12 * (1 + combined[i].norm()));
}

// apply() on a container held in place (rope/common/fixed_vector.h, what the removal checks use to
// allocate nothing) gives bitwise what it gives on a std::vector, for both sides; so does
// KnotInsertion::apply, and a FixedVector refuses to grow past its capacity.
TEST(KnotRemoval, ApplyOnAnInPlaceWindowEqualsApplyOnAVector) {
  std::mt19937 rng(23);
  for (int trial = 0; trial < 50; ++trial) {
    const BSplineCurve curve = test::randomCurve(rng, 3, true, 1);
    const std::vector<double> interior = interiorKnots(curve.knots());
    if (interior.empty()) continue;
    const KnotRemoval removal = planKnotRemoval(curve.knots(), curve.controlPoints(), interior.front());
    for (const KnotRemoval::Side side : {KnotRemoval::kFromLeft, KnotRemoval::kFromRight}) {
      PointList vector = curve.controlPoints();
      FixedVector<Vec3, 32> window;
      window.assign(vector.begin(), vector.end());
      removal.apply(vector, side);
      removal.apply(window, side);
      ASSERT_EQ(window.size(), vector.size());
      for (size_t i = 0; i < vector.size(); ++i) EXPECT_EQ(window[i], vector[i]);
    }
    const KnotInsertion insertion = planKnotInsertion(curve.knots(), interior.front());
    PointList vector = curve.controlPoints();
    FixedVector<Vec3, 32> window;
    window.assign(vector.begin(), vector.end());
    insertion.apply(vector);
    insertion.apply(window);
    ASSERT_EQ(window.size(), vector.size());
    for (size_t i = 0; i < vector.size(); ++i) EXPECT_EQ(window[i], vector[i]);
  }
  FixedVector<double, 2> full;
  full.push_back(1.0);
  full.push_back(2.0);
  EXPECT_THROW(full.push_back(3.0), std::length_error);
  EXPECT_THROW(full.insert(full.begin(), 0.0), std::length_error);
  EXPECT_EQ(full.size(), 2u);
  EXPECT_EQ(full[0], 1.0);
  full.erase(full.begin());
  ASSERT_EQ(full.size(), 1u);
  EXPECT_EQ(full[0], 2.0);
}

// ---- bad input ----

TEST(KnotRemovalBadInput, RemovingAKnotThatIsNotThere) {
  BSplineCurve curve(KnotVector::clampedUniform(3, 8), PointList(8, Vec3(1, 0, 0)));
  const BSplineCurve before = curve;
  expectInvalid([&] { curve.removeKnot(0.3); }, "s", "0.29999999999999999");
  expectInvalid([&] { curve.removeKnot(0.0); }, "s", "0");  // an end knot is not removable
  EXPECT_EQ(curve.knots().values(), before.knots().values());
  EXPECT_EQ(curve.controlPoints(), before.controlPoints());
}

TEST(KnotRemovalBadInput, NonFiniteParameterOrPoint) {
  BSplineCurve curve(KnotVector::clampedUniform(2, 6), PointList(6, Vec3(1, 0, 0)));
  const BSplineCurve before = curve;
  expectInvalid([&] { curve.removeKnot(std::nan("")); }, "s", "nan");
  EXPECT_EQ(curve.knots().values(), before.knots().values());
  EXPECT_EQ(curve.controlPoints(), before.controlPoints());
  KnotVector knots = KnotVector::clampedUniform(2, 6);
  PointList points(6, Vec3::Zero());
  points[3].z() = std::nan("");
  const PointList pointsBefore = points;
  expectInvalid([&] { removeKnot(knots, points, 0.5); }, "points[3]", "nan");
  EXPECT_EQ(knots.values(), KnotVector::clampedUniform(2, 6).values());
  EXPECT_TRUE(points[3].hasNaN());
  EXPECT_EQ(points[2], pointsBefore[2]);
}

TEST(KnotRemovalBadInput, PointCountNotMatchingTheKnots) {
  KnotVector knots(3, {0, 0, 0, 0, 0.5, 1, 1, 1, 1});
  PointList points(4, Vec3::Zero());  // the knots need 5
  const PointList pointsBefore = points;
  expectInvalid([&] { removeKnot(knots, points, 0.5); }, "points.size()", "4");
  EXPECT_EQ(knots.values(), (std::vector<double>{0, 0, 0, 0, 0.5, 1, 1, 1, 1}));
  EXPECT_EQ(points, pointsBefore);
}

}  // namespace
}  // namespace rope
