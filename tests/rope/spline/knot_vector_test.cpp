// SPDX-License-Identifier: MIT
#include "rope/spline/knot_vector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "rope/common/error.h"
#include "tests/rope/spline/spline_test_support.h"

namespace rope {
namespace {

using test::expectInvalid;

TEST(KnotVector, ClampedUniformHasRepeatedEndsAndEvenInterior) {
  const KnotVector knots = KnotVector::clampedUniform(3, 7, 2.0, 6.0);
  const std::vector<double> expected{2, 2, 2, 2, 3, 4, 5, 6, 6, 6, 6};
  EXPECT_EQ(knots.values(), expected);
  EXPECT_EQ(knots.controlPointCount(), 7);
  EXPECT_EQ(knots.validBegin(), 2.0);
  EXPECT_EQ(knots.validEnd(), 6.0);
  EXPECT_TRUE(knots.isClampedBegin());
  EXPECT_TRUE(knots.isClampedEnd());
}

TEST(KnotVector, UniformMatchesPaperExample) {
  // [A]'s example: {0, 1, ..., 14} for 11 cubic control points, valid range [3, 11].
  const KnotVector knots = KnotVector::uniform(3, 11);
  ASSERT_EQ(knots.size(), 15);
  for (int i = 0; i < 15; ++i) EXPECT_EQ(knots[i], i);
  EXPECT_EQ(knots.validBegin(), 3.0);
  EXPECT_EQ(knots.validEnd(), 11.0);
  EXPECT_FALSE(knots.isClampedBegin());
  EXPECT_FALSE(knots.isClampedEnd());
}

TEST(KnotVector, FindSpanSatisfiesDefinitionOnRandomVectorsAlsoFromAnyHint) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 400; ++trial) {
    const int degree = 1 + trial % kMaxDegree;
    const KnotVector knots = test::randomKnots(rng, degree, degree + 1 + trial % 9, trial % 2 == 0, degree + 1);
    for (double s : test::sampleParameters(rng, knots, 30)) {
      const int k = knots.findSpan(s);
      ASSERT_GE(k, degree);
      ASSERT_LE(k, knots.controlPointCount() - 1);
      ASSERT_LT(knots[k], knots[k + 1]) << "span must be non-empty";
      ASSERT_LE(knots[k], s);
      if (s < knots.validEnd()) {
        ASSERT_LT(s, knots[k + 1]);
      } else {
        ASSERT_EQ(knots[k + 1], knots.validEnd());
      }
      ASSERT_EQ(knots.findSpanUnchecked(s), k);
      // findSpanNear from any hint: the right span, the one before it (stepping over empty spans),
      // far ones, -1 and past the last span.
      for (int hint = -1; hint <= knots.controlPointCount() + 1; ++hint) {
        ASSERT_EQ(knots.findSpanNear(s, hint), k) << "s = " << s << ", hint " << hint;
      }
    }
  }
}

TEST(KnotVector, MultiplicityCountsEqualKnots) {
  const KnotVector knots(2, {0, 0, 0, 1, 1, 2, 3, 3, 3});
  EXPECT_EQ(knots.multiplicity(0.0), 3);
  EXPECT_EQ(knots.multiplicity(1.0), 2);
  EXPECT_EQ(knots.multiplicity(2.0), 1);
  EXPECT_EQ(knots.multiplicity(1.5), 0);
  EXPECT_EQ(knots.multiplicity(std::nan("")), 0);
  EXPECT_EQ(knots.findSpan(1.0), 4);  // after the repeated knot
  EXPECT_EQ(knots.findSpan(3.0), 5);  // end: last non-empty span
}

TEST(KnotVector, ContainsOnlyTheValidRange) {
  const KnotVector knots = KnotVector::uniform(2, 4);  // valid [2, 4]
  EXPECT_TRUE(knots.contains(2.0));
  EXPECT_TRUE(knots.contains(4.0));
  EXPECT_FALSE(knots.contains(1.999));
  EXPECT_FALSE(knots.contains(4.001));
  EXPECT_FALSE(knots.contains(std::nan("")));
  EXPECT_FALSE(knots.contains(std::numeric_limits<double>::infinity()));
}

TEST(KnotVector, InsertValueAndEraseAtKeepOrder) {
  KnotVector knots(2, {0, 0, 0, 1, 2, 2, 2});
  knots.insertValue(1.0);
  EXPECT_EQ(knots.values(), (std::vector<double>{0, 0, 0, 1, 1, 2, 2, 2}));
  knots.insertValue(0.5);
  EXPECT_EQ(knots.values(), (std::vector<double>{0, 0, 0, 0.5, 1, 1, 2, 2, 2}));
  knots.eraseAt(4);
  EXPECT_EQ(knots.values(), (std::vector<double>{0, 0, 0, 0.5, 1, 2, 2, 2}));
}

// ---- bad input: every error names the parameter and its value; nothing changes ----

TEST(KnotVectorBadInput, NonMonotoneKnots) {
  expectInvalid([] { KnotVector(2, {0, 0, 0, 2, 1, 3, 3, 3}); }, "knots[4]", "1");
  expectInvalid([] { KnotVector::clampedUniform(2, 4, 1.0, 0.5); }, "end", "0.5");
}

TEST(KnotVectorBadInput, TooFewControlPointsForDegree) {
  expectInvalid([] { KnotVector(3, {0, 0, 0, 1, 1, 1}); }, "knots.size()", "6");
  expectInvalid([] { KnotVector::clampedUniform(3, 3); }, "controlPointCount", "3");
  // Erasing would leave d control points: the vector stays as it was.
  KnotVector knots(1, {0, 0, 1, 1});
  const std::vector<double> before = knots.values();
  expectInvalid([&] { knots.eraseAt(1); }, "knots.size()", "3");
  EXPECT_EQ(knots.values(), before);
}

TEST(KnotVectorBadInput, DegreeOutOfRange) {
  expectInvalid([] { KnotVector(0, {0, 1}); }, "degree", "0");
  expectInvalid([] { KnotVector(6, std::vector<double>(14, 0.0)); }, "degree", "6");
  expectInvalid([] { KnotVector::uniform(-1, 4); }, "degree", "-1");
}

TEST(KnotVectorBadInput, NonFiniteKnots) {
  const double inf = std::numeric_limits<double>::infinity();
  expectInvalid([] { KnotVector(1, {0, 0, std::nan(""), 1}); }, "knots[2]", "nan");
  expectInvalid([&] { KnotVector(1, {-inf, 0, 1, 1}); }, "knots[0]", "-inf");
  KnotVector knots = KnotVector::uniform(2, 5);
  const std::vector<double> before = knots.values();
  expectInvalid([&] { knots.insertValue(std::nan("")); }, "s", "nan");
  EXPECT_EQ(knots.values(), before);
}

TEST(KnotVectorBadInput, ParameterOutsideValidRange) {
  const KnotVector knots = KnotVector::uniform(3, 6);  // valid [3, 6]
  expectInvalid([&] { knots.findSpan(6.5); }, "s", "6.5");
  expectInvalid([&] { knots.findSpan(std::nan("")); }, "s", "nan");
}

TEST(KnotVectorBadInput, EmptyValidRangeAndExcessMultiplicity) {
  expectInvalid([] { KnotVector(1, {0, 1, 1, 2}); }, "knots[2]", "1");           // s_1 == s_2
  expectInvalid([] { KnotVector(1, {0, 0, 0, 1, 1}); }, "knots[2]", "0");        // 3 > d+1
  KnotVector knots(1, {0, 0, 0.5, 0.5, 1, 1});
  const std::vector<double> before = knots.values();
  expectInvalid([&] { knots.insertValue(0.5); }, "s", "0.5");  // beyond multiplicity d+1
  EXPECT_EQ(knots.values(), before);
  expectInvalid([&] { knots.eraseAt(9); }, "index", "9");
  EXPECT_EQ(knots.values(), before);
}

}  // namespace
}  // namespace rope
