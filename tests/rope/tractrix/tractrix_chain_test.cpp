// SPDX-License-Identifier: MIT
// The chain pass: exact segment lengths, decaying displacements ([B] §2.1), bad input.
#include "rope/tractrix/tractrix_chain.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rope/common/error.h"
#include "rope/tractrix/tractrix_segment.h"

namespace rope {
namespace {

// A random chain: n segments with lengths in [0.2, 1.2] and random 3D directions.
void randomChain(std::mt19937_64& rng, int n, PointList& points, std::vector<double>& lengths) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> length(0.2, 1.2);
  points.assign(1, Vec3::Zero());
  lengths.clear();
  for (int i = 0; i < n; ++i) {
    const Vec3 direction = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    lengths.push_back(length(rng));
    points.push_back(points.back() - lengths.back() * direction);
  }
}

TEST(TractrixChain, KeepsEverySegmentLengthAndDisplacementsDecay) {
  std::mt19937_64 rng(2024);
  std::normal_distribution<double> normal;
  double worstLength = 0.0;
  for (int path = 0; path < 20; ++path) {
    PointList points;
    std::vector<double> lengths;
    randomChain(rng, 40, points, lengths);
    Vec3 leading = points[0];
    for (int step = 0; step < 200; ++step) {
      // A random walk of the leading end with steps up to a few segment lengths.
      leading += 0.7 * Vec3(normal(rng), normal(rng), normal(rng));
      const PointList before = points;
      tractrixChainPass(points, lengths, leading);
      EXPECT_EQ(points[0], leading);
      double previous = (points[0] - before[0]).norm();
      for (size_t i = 0; i < lengths.size(); ++i) {
        worstLength = std::max(worstLength, std::fabs((points[i + 1] - points[i]).norm() - lengths[i]));
        // [B] §2.1: dr_0 >= dr_1 >= ... >= dr_n (with rounding slack).
        const double moved = (points[i + 1] - before[i + 1]).norm();
        ASSERT_LE(moved, previous + 1e-12) << "path " << path << " step " << step << " point " << i + 1;
        previous = moved;
      }
    }
  }
  EXPECT_LT(worstLength, 1e-12);
  RecordProperty("worst_segment_length_error", formatValue(worstLength));
}

TEST(TractrixChain, EachSegmentFollowsTheClosedForm) {
  std::mt19937_64 rng(5);
  PointList points;
  std::vector<double> lengths;
  randomChain(rng, 6, points, lengths);
  const PointList before = points;
  const Vec3 target(0.4, -0.3, 0.9);
  tractrixChainPass(points, lengths, target);
  Vec3 leading = target;
  for (size_t i = 0; i < lengths.size(); ++i) {
    const Vec3 expected = tractrixMoveTrailing(before[i], before[i + 1], leading, lengths[i]);
    EXPECT_EQ(points[i + 1], expected) << i;
    leading = expected;
  }
}

TEST(TractrixChain, NoMoveChangesNothing) {
  std::mt19937_64 rng(6);
  PointList points;
  std::vector<double> lengths;
  randomChain(rng, 10, points, lengths);
  const PointList before = points;
  tractrixChainPass(points, lengths, points[0]);
  EXPECT_EQ(points, before);
}

TEST(TractrixChain, StraightPullTranslatesAStraightChain) {
  // alpha = 0 for every segment: the chain moves rigidly.
  PointList points;
  std::vector<double> lengths(5, 0.5);
  for (int i = 0; i <= 5; ++i) points.emplace_back(-0.5 * i, 0.0, 0.0);
  tractrixChainPass(points, lengths, Vec3(2.0, 0.0, 0.0));
  for (int i = 0; i <= 5; ++i) EXPECT_NEAR((points[static_cast<size_t>(i)] - Vec3(2.0 - 0.5 * i, 0, 0)).norm(), 0.0, 1e-14);
}

TEST(TractrixChain, RejectsBadInputAndLeavesPointsUnchanged) {
  PointList points = {Vec3(0, 0, 0), Vec3(-1, 0, 0), Vec3(-2, 0, 0)};
  const PointList original = points;
  const std::vector<double> lengths = {1.0, 1.0};
  EXPECT_THROW(tractrixChainPass(points, lengths, Vec3(std::nan(""), 0, 0)), InvalidArgument);
  EXPECT_THROW(tractrixChainPass(points, lengths, Vec3(0, -HUGE_VAL, 0)), InvalidArgument);
  EXPECT_THROW(tractrixChainPass(points, lengths, Vec3(0, 0, 1e250)), InvalidArgument);
  EXPECT_THROW(tractrixChainPass(points, {1.0}, Vec3(1, 0, 0)), InvalidArgument);
  PointList single = {Vec3::Zero()};
  EXPECT_THROW(tractrixChainPass(single, {}, Vec3(1, 0, 0)), InvalidArgument);
  EXPECT_EQ(points, original);

  EXPECT_NO_THROW(validateTractrixChain(points, lengths));
  EXPECT_THROW(validateTractrixChain(points, {1.0, 0.0}), InvalidArgument);
  EXPECT_THROW(validateTractrixChain(points, {1.0, -2.0}), InvalidArgument);
  EXPECT_THROW(validateTractrixChain(points, {1.0, std::nan("")}), InvalidArgument);
  EXPECT_THROW(validateTractrixChain({Vec3(0, 0, 0), Vec3(std::nan(""), 0, 0)}, {1.0}), InvalidArgument);
  EXPECT_THROW(validateTractrixChain(points, {1.0}), InvalidArgument);
}

}  // namespace
}  // namespace rope
