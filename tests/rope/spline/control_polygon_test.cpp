// SPDX-License-Identifier: MIT
#include "rope/spline/control_polygon.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "tests/rope/spline/spline_test_support.h"

namespace rope {
namespace {

using test::expectInvalid;

const double kPi = std::acos(-1.0);

// Three points with sides of lengths la, lb meeting at q_1 with the given included angle.
PointList corner(double includedAngle, double la = 1.0, double lb = 1.0) {
  const double turn = kPi - includedAngle;
  return PointList{Vec3(-la, 0, 0), Vec3::Zero(), lb * Vec3(std::cos(turn), std::sin(turn), 0)};
}

TEST(ControlPolygon, BendMeasureOfStraightFoldedAndRightAngle) {
  EXPECT_EQ(bendMeasure(PointList{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(3, 0, 0)}, 1), 0.0);
  EXPECT_EQ(bendMeasure(PointList{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 0, 0)}, 1), 1.0);
  EXPECT_NEAR(bendMeasure(PointList{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 5, 0)}, 1), 0.5, 1e-16);
  EXPECT_NEAR(includedAngle(PointList{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(3, 0, 0)}, 1), kPi, 1e-15);
  EXPECT_NEAR(includedAngle(PointList{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 0, 0)}, 1), 0.0, 1e-15);
  EXPECT_NEAR(includedAngle(PointList{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 5, 0)}, 1), kPi / 2, 1e-15);
}

TEST(ControlPolygon, BendMeasureIsOnePlusCosineOfIncludedAngleOverTwo) {
  std::mt19937 rng(61);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    PointList points;
    for (int i = 0; i < 6; ++i) points.push_back(Vec3(unit(rng), unit(rng), unit(rng)));
    for (int i = 1; i <= 4; ++i) {
      const double c = bendMeasure(points, i);
      const double theta = includedAngle(points, i);
      EXPECT_GE(c, 0.0);
      EXPECT_LE(c, 1.0);
      EXPECT_NEAR(c, 0.5 * (1.0 + std::cos(theta)), 1e-14);
      EXPECT_NEAR(c, bendMeasureFromAngle(theta), 1e-14);
      // The angle form is well conditioned away from the ends; acos is not near c = 0 or 1.
      if (c > 1e-6 && c < 1 - 1e-6) {
        EXPECT_NEAR(angleFromBendMeasure(c), theta, 1e-6);
      }
    }
  }
}

TEST(ControlPolygon, ThresholdsOfSpec3) {
  // [B]'s 140 degrees (subdivide) and 160 degrees (merge), both as corners and as conversions.
  EXPECT_NEAR(bendMeasureFromAngle(140.0 * kPi / 180.0), 0.117, 5e-4);
  EXPECT_NEAR(bendMeasureFromAngle(160.0 * kPi / 180.0), 0.030, 5e-4);
  EXPECT_NEAR(bendMeasure(corner(140.0 * kPi / 180.0, 0.3, 2.0), 1), 0.5 * (1 + std::cos(140.0 * kPi / 180.0)), 1e-15);
  EXPECT_NEAR(includedAngle(corner(160.0 * kPi / 180.0, 5.0, 0.1), 1), 160.0 * kPi / 180.0, 1e-14);
  EXPECT_NEAR(angleFromBendMeasure(0.5 * (1 + std::cos(140.0 * kPi / 180.0))) * 180.0 / kPi, 140.0, 1e-12);
}

TEST(ControlPolygon, ZeroLengthSideDoesNotBend) {
  const PointList points{Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(1, 1, 0), Vec3(0, 3, 0)};
  EXPECT_EQ(bendMeasure(points, 1), 0.0);
  EXPECT_EQ(includedAngle(points, 2), kPi);
}

// The window overload (a polygon held anywhere, here inside a larger one) is the same function.
TEST(ControlPolygon, BendMeasureOfAWindowEqualsTheWholePolygons) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  PointList points;
  for (int i = 0; i < 12; ++i) points.emplace_back(unit(rng), unit(rng), unit(rng));
  for (int first = 0; first + 3 <= 12; ++first) {
    for (int i = 1; i + 1 < 12 - first; ++i) {
      EXPECT_EQ(bendMeasure(points.data() + first, points.size() - static_cast<size_t>(first), i),
                bendMeasure(points, first + i));
    }
  }
  PointList bad = points;
  bad[4] = Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  expectInvalid([&] { bendMeasure(bad.data(), bad.size(), 3); }, "points[4]", "nan");
  expectInvalid([&] { bendMeasure(bad.data(), 3, 2); }, "i", "2");
}

TEST(ControlPolygon, PolygonLengthSumsSides) {
  EXPECT_EQ(polygonLength(PointList{Vec3(0, 0, 0), Vec3(3, 4, 0), Vec3(3, 4, 2)}), 7.0);
  EXPECT_EQ(polygonLength(PointList{Vec3(1, 1, 1)}), 0.0);
  EXPECT_EQ(polygonLength(PointList{}), 0.0);
}

// ---- bad input ----

TEST(ControlPolygonBadInput, VertexIndexOutOfRange) {
  const PointList points{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 1, 0)};
  expectInvalid([&] { bendMeasure(points, 0); }, "i", "0");
  expectInvalid([&] { includedAngle(points, 2); }, "i", "2");
}

TEST(ControlPolygonBadInput, NonFinitePointsAndValues) {
  PointList points{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 1, 0)};
  points[2].x() = std::numeric_limits<double>::infinity();
  expectInvalid([&] { bendMeasure(points, 1); }, "points[2]", "inf");
  points[2].x() = std::nan("");
  expectInvalid([&] { polygonLength(points); }, "points[2]", "nan");
  expectInvalid([] { bendMeasureFromAngle(std::nan("")); }, "includedAngleRadians", "nan");
  expectInvalid([] { bendMeasureFromAngle(4.0); }, "includedAngleRadians", "4");
  expectInvalid([] { angleFromBendMeasure(1.5); }, "bendMeasure", "1.5");
}

}  // namespace
}  // namespace rope
