// SPDX-License-Identifier: MIT
#include "rope/spline/curve_interpolation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "tests/rope/spline/spline_test_support.h"

namespace rope {
namespace {

using test::expectInvalid;

PointList randomPolyline(std::mt19937& rng, int count) {
  std::uniform_real_distribution<double> step(-1.0, 1.0);
  std::uniform_real_distribution<double> length(0.05, 2.0);
  PointList points{Vec3(step(rng), step(rng), step(rng))};
  for (int i = 1; i < count; ++i) {
    Vec3 direction(step(rng), step(rng), step(rng));
    if (direction.norm() < 1e-3) direction = Vec3::UnitX();
    points.push_back(points.back() + length(rng) * direction.normalized());
  }
  return points;
}

TEST(CurveInterpolation, PassesThroughEveryPoint) {
  std::mt19937 rng(41);
  double worst = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    const int degree = 1 + trial % kMaxDegree;
    const Parametrization parametrization =
        (trial / kMaxDegree) % 2 == 0 ? Parametrization::kChordLength : Parametrization::kCentripetal;
    const PointList points = randomPolyline(rng, degree + 1 + trial % 40);
    const Interpolation result = interpolatePolyline(points, degree, parametrization);
    ASSERT_EQ(result.parameters.size(), points.size());
    ASSERT_EQ(result.curve.degree(), degree);
    ASSERT_EQ(result.curve.controlPointCount(), static_cast<int>(points.size()));
    EXPECT_TRUE(result.curve.knots().isClampedBegin());
    EXPECT_TRUE(result.curve.knots().isClampedEnd());
    for (size_t i = 0; i < points.size(); ++i) {
      worst = std::max(worst, (result.curve.position(result.parameters[i]) - points[i]).norm());
    }
  }
  std::printf("interpolation: max |C(s_k) - Q_k| = %.3g m\n", worst);
  EXPECT_LE(worst, 1e-10);
}

TEST(CurveInterpolation, ParametersSpanTheTotalChordLength) {
  std::mt19937 rng(42);
  const PointList points = randomPolyline(rng, 12);
  double total = 0.0;
  for (size_t i = 1; i < points.size(); ++i) total += (points[i] - points[i - 1]).norm();
  for (Parametrization parametrization : {Parametrization::kChordLength, Parametrization::kCentripetal}) {
    const Interpolation result = interpolatePolyline(points, 3, parametrization);
    EXPECT_EQ(result.parameters.front(), 0.0);
    EXPECT_EQ(result.parameters.back(), total);
    EXPECT_EQ(result.curve.beginParameter(), 0.0);
    EXPECT_EQ(result.curve.endParameter(), total);
    EXPECT_TRUE(std::is_sorted(result.parameters.begin(), result.parameters.end()));
  }
  // Chord length: parameter steps are the chord lengths themselves.
  const Interpolation chord = interpolatePolyline(points, 3, Parametrization::kChordLength);
  for (size_t i = 1; i < points.size(); ++i) {
    EXPECT_NEAR(chord.parameters[i] - chord.parameters[i - 1], (points[i] - points[i - 1]).norm(), 1e-12 * total);
  }
}

TEST(CurveInterpolation, KnotsAreAveragedParameters) {
  // Piegl & Tiller eq. 9.8 on a small example: u_{j+p} = (1/p) sum_{i=j}^{j+p-1} s_i.
  const PointList points{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 2, 0), Vec3(1, 2, 2), Vec3(4, 2, 2), Vec3(4, 6, 2)};
  const Interpolation result = interpolatePolyline(points, 3);
  const std::vector<double> s{0, 1, 3, 5, 8, 12};
  EXPECT_EQ(result.parameters, s);
  const std::vector<double> expected{0, 0, 0, 0, (1 + 3 + 5) / 3.0, (3 + 5 + 8) / 3.0, 12, 12, 12, 12};
  const std::vector<double>& knots = result.curve.knots().values();
  ASSERT_EQ(knots.size(), expected.size());
  for (size_t i = 0; i < knots.size(); ++i) EXPECT_NEAR(knots[i], expected[i], 1e-15 * 12);
}

TEST(CurveInterpolation, StraightPointsGiveAStraightCurve) {
  PointList points;
  for (int i = 0; i < 9; ++i) points.push_back(Vec3(0.5 * i * i, 0.5 * i * i, 0));  // uneven spacing
  const Interpolation result = interpolatePolyline(points, 3);
  for (const Vec3& q : result.curve.controlPoints()) {
    EXPECT_NEAR(q.x(), q.y(), 1e-12 * 32);
    EXPECT_EQ(q.z(), 0.0);
  }
}

TEST(CurveInterpolation, ScalesToLongPolylines) {
  // 20,000 points: the banded solve is O(n); a dense one would not finish in the test's time.
  std::mt19937 rng(43);
  const PointList points = randomPolyline(rng, 20000);
  const Interpolation result = interpolatePolyline(points, 3);
  double worst = 0.0;
  for (size_t i = 0; i < points.size(); i += 97) {
    worst = std::max(worst, (result.curve.position(result.parameters[i]) - points[i]).norm());
  }
  EXPECT_LE(worst, 1e-10);
}

// ---- bad input ----

TEST(CurveInterpolationBadInput, DegreeOutOfRange) {
  const PointList points{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 1, 0), Vec3(3, 1, 0), Vec3(4, 0, 0), Vec3(5, 0, 0), Vec3(6, 1, 1)};
  expectInvalid([&] { interpolatePolyline(points, 0); }, "degree", "0");
  expectInvalid([&] { interpolatePolyline(points, 6); }, "degree", "6");
}

TEST(CurveInterpolationBadInput, TooFewPointsForTheDegree) {
  const PointList points{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 1, 0)};
  expectInvalid([&] { interpolatePolyline(points, 3); }, "points.size()", "3");
}

TEST(CurveInterpolationBadInput, NonFiniteOrCoincidentPoints) {
  PointList points{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 1, 0), Vec3(3, 1, 0), Vec3(4, 0, 0)};
  PointList bad = points;
  bad[3].y() = std::numeric_limits<double>::infinity();
  expectInvalid([&] { interpolatePolyline(bad, 3); }, "points[3]", "inf");
  bad = points;
  bad[0].x() = std::nan("");
  expectInvalid([&] { interpolatePolyline(bad, 2, Parametrization::kCentripetal); }, "points[0]", "nan");
  bad = points;
  bad[2] = bad[1];
  expectInvalid([&] { interpolatePolyline(bad, 3); }, "points[2]", "coincides with points[1]");
}

}  // namespace
}  // namespace rope
