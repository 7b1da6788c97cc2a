// SPDX-License-Identifier: MIT
#include "rope/rod/banded_matrix.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace rope {
namespace {

// A random symmetric positive definite block-banded matrix, filled through the public interface, and
// the same matrix densely (the test's reference; dense only here).
Eigen::MatrixXd randomBanded(int blocks, int blockSize, int bandwidth, unsigned seed,
                             SymmetricBandedMatrix& banded) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  banded.reset(blocks, blockSize, bandwidth);
  const int n = blocks * blockSize;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  const int w = banded.halfBandwidth();
  for (int r = 0; r < n; ++r) {
    for (int c = std::max(0, r - w); c < r; ++c) {
      const double value = uniform(rng);
      banded.at(r, c) = value;
      dense(r, c) = dense(c, r) = value;
    }
  }
  for (int r = 0; r < n; ++r) {
    const double value = 2.0 * w + 1.0 + uniform(rng);  // diagonally dominant
    banded.at(r, r) = value;
    dense(r, r) = value;
  }
  return dense;
}

TEST(SymmetricBandedMatrix, BandwidthFollowsBlocks) {
  SymmetricBandedMatrix m;
  m.reset(10, 3, 3);
  EXPECT_EQ(m.size(), 30);
  EXPECT_EQ(m.halfBandwidth(), 11);
  m.reset(10, 1, 3);
  EXPECT_EQ(m.halfBandwidth(), 3);
}

TEST(SymmetricBandedMatrix, MultiplyMatchesDense) {
  for (int blockSize : {1, 3}) {
    SymmetricBandedMatrix banded;
    const Eigen::MatrixXd dense = randomBanded(17, blockSize, 3, 11u + static_cast<unsigned>(blockSize), banded);
    const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(dense.rows(), -1.0, 2.0);
    Eigen::VectorXd y(dense.rows());
    banded.multiply(x.data(), y.data());
    EXPECT_LT((y - dense * x).norm(), 1e-12 * (dense * x).norm());
    for (int r = 0; r < dense.rows(); ++r)
      for (int c = 0; c < dense.cols(); ++c) EXPECT_EQ(banded.entry(r, c), dense(r, c));
  }
}

TEST(SymmetricBandedMatrix, SolveMatchesDense) {
  for (int bandwidth : {1, 2, 3, 5}) {
    SymmetricBandedMatrix banded;
    const Eigen::MatrixXd dense = randomBanded(23, 3, bandwidth, 5u + static_cast<unsigned>(bandwidth), banded);
    Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(dense.rows(), 1.0, -3.0);
    const Eigen::VectorXd expected = dense.ldlt().solve(b);
    ASSERT_TRUE(banded.factorize());
    EXPECT_TRUE(banded.factorized());
    banded.solve(b.data());
    EXPECT_LT((b - expected).norm(), 1e-12 * expected.norm()) << "bandwidth " << bandwidth;
  }
}

TEST(SymmetricBandedMatrix, FactorIsBitwiseTheTextbookRowByRowOne) {
  // factorize() updates the trailing band column by column; every entry must still receive its terms
  // in the order of L(r, c) = (A(r, c) - sum_{k ascending} L(r, k) L(c, k)) * (1 / L(c, c)), so that
  // the rounding (and every golden hash built on it) is that of the textbook form, with the pivot's
  // reciprocal taken once per column.
  for (int blockSize : {1, 3}) {
    SymmetricBandedMatrix banded;
    const Eigen::MatrixXd dense = randomBanded(19, blockSize, 3, 21u + static_cast<unsigned>(blockSize), banded);
    const int n = static_cast<int>(dense.rows());
    const int w = banded.halfBandwidth();
    Eigen::MatrixXd lower = Eigen::MatrixXd::Zero(n, n);
    for (int r = 0; r < n; ++r) {
      for (int c = std::max(0, r - w); c <= r; ++c) {
        double sum = dense(r, c);
        for (int k = std::max(0, r - w); k < c; ++k) sum -= lower(r, k) * lower(c, k);
        lower(r, c) = c < r ? sum * (1.0 / lower(c, c)) : std::sqrt(sum);
      }
    }
    ASSERT_TRUE(banded.factorize());
    for (int r = 0; r < n; ++r)
      for (int c = std::max(0, r - w); c <= r; ++c) ASSERT_EQ(banded.entry(r, c), lower(r, c)) << r << ", " << c;
  }
}

TEST(SymmetricBandedMatrix, ForwardSubstitutionSkipsLeadingZeros) {
  SymmetricBandedMatrix banded;
  const Eigen::MatrixXd dense = randomBanded(12, 3, 3, 77u, banded);
  ASSERT_TRUE(banded.factorize());
  const Eigen::MatrixXd L = dense.llt().matrixL();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(dense.rows());
  x(20) = 1.0;
  x(23) = -0.5;
  const Eigen::VectorXd expected = L.triangularView<Eigen::Lower>().solve(x);
  banded.forwardSubstitute(x.data(), 20);
  EXPECT_LT((x - expected).norm(), 1e-12 * expected.norm());
}

// Three right-hand sides substituted together are each the one-column substitution, bit for bit; a
// back substitution that stops at lastRow gives the same bits on the rows from lastRow on.
TEST(SymmetricBandedMatrix, ThreeColumnSubstitutionsAreTheOneColumnOnesAndStopWhereAsked) {
  SymmetricBandedMatrix banded;
  const Eigen::MatrixXd dense = randomBanded(12, 3, 3, 91u, banded);
  ASSERT_TRUE(banded.factorize());
  const int n = static_cast<int>(dense.rows());
  const int firstRow = 7;
  Eigen::MatrixXd columns = Eigen::MatrixXd::Zero(n, 3);
  for (int c = 0; c < 3; ++c)
    for (int r = firstRow; r < n; ++r) columns(r, c) = std::sin(1.0 + r + 7.0 * c);
  Eigen::MatrixXd single = columns;
  for (int c = 0; c < 3; ++c) {
    banded.forwardSubstitute(single.col(c).data(), firstRow);
    banded.backSubstitute(single.col(c).data());
  }
  for (const int lastRow : {-1, 0, 1, 13, n - 1}) {  // before the first row: all of it
    Eigen::MatrixXd together = columns;
    banded.forwardSubstitute3(together.data(), firstRow);
    banded.backSubstitute3(together.data(), lastRow);
    for (int c = 0; c < 3; ++c)
      for (int r = std::max(lastRow, 0); r < n; ++r)
        EXPECT_EQ(together(r, c), single(r, c)) << "lastRow " << lastRow << " row " << r;
  }
  // And the substitutions solve the system.
  EXPECT_LT((dense * single - columns).norm(), 1e-12 * columns.norm());
}

// Constraint columns substituted together, each from its own first row (a few rows apart, or more than
// a half bandwidth apart), are each the one-column substitution, bit for bit.
TEST(SymmetricBandedMatrix, ColumnsSubstitutedTogetherAreEachTheirOwnSubstitution) {
  SymmetricBandedMatrix banded;
  const Eigen::MatrixXd dense = randomBanded(12, 3, 3, 57u, banded);
  ASSERT_TRUE(banded.factorize());
  const int n = static_cast<int>(dense.rows());
  const int w = banded.halfBandwidth();
  const std::vector<std::vector<int>> cases = {{0, 1, 2}, {2, 0, 1}, {3, 3 + w, 20}, {5}, {7, 9},
                                               {0, n - 1, n - 2}, {n, 4}, {0, 1, 2, 30, 31}};
  for (const std::vector<int>& firstRows : cases) {
    const int count = static_cast<int>(firstRows.size());
    Eigen::MatrixXd columns = Eigen::MatrixXd::Zero(n, count);
    for (int k = 0; k < count; ++k)
      for (int r = firstRows[static_cast<size_t>(k)]; r < n; ++r) columns(r, k) = std::cos(0.3 + r + 5.0 * k);
    Eigen::MatrixXd single = columns;
    for (int k = 0; k < count; ++k) banded.forwardSubstitute(single.col(k).data(), firstRows[static_cast<size_t>(k)]);
    Eigen::MatrixXd together = columns;
    double* pointers[5];
    for (int k = 0; k < count; ++k) pointers[k] = together.col(k).data();
    banded.forwardSubstituteColumns(pointers, firstRows.data(), count);
    for (int k = 0; k < count; ++k)
      for (int r = 0; r < n; ++r) EXPECT_EQ(together(r, k), single(r, k)) << "column " << k << " of " << count << " row " << r;
  }
}

TEST(SymmetricBandedMatrix, BlocksAddSymmetrically) {
  SymmetricBandedMatrix m;
  m.reset(4, 3, 1);
  Eigen::Matrix3d block;
  block << 1, 2, 3, 4, 5, 6, 7, 8, 9;
  m.addBlock(2, 1, block);
  EXPECT_EQ(m.entry(6, 3), 1.0);
  EXPECT_EQ(m.entry(3, 6), 1.0);
  EXPECT_EQ(m.entry(7, 5), 6.0);
  m.addScaledIdentity(3, 3, 2.5);
  EXPECT_EQ(m.entry(10, 10), 2.5);
  EXPECT_EQ(m.entry(10, 9), 0.0);
  EXPECT_EQ(m.entry(11, 0), 0.0);  // outside the band
}

TEST(SymmetricBandedMatrix, IndefiniteMatrixReportsFailureWithoutNaN) {
  SymmetricBandedMatrix m;
  m.reset(5, 1, 1);
  for (int i = 0; i < 5; ++i) m.at(i, i) = 1.0;
  m.at(3, 2) = 2.0;  // [[1,2],[2,1]] block: indefinite
  EXPECT_FALSE(m.factorize());
  EXPECT_FALSE(m.factorized());
  SymmetricBandedMatrix zero;
  zero.reset(3, 3, 1);
  EXPECT_FALSE(zero.factorize());
}

TEST(SymmetricBandedMatrix, ResetClearsAndReusesStorage) {
  SymmetricBandedMatrix banded;
  randomBanded(30, 3, 3, 3u, banded);
  banded.reset(4, 3, 3);
  for (int r = 0; r < banded.size(); ++r)
    for (int c = 0; c < banded.size(); ++c) EXPECT_EQ(banded.entry(r, c), 0.0);
}

// A rod that coarsens (16 -> 4 control points on a floor) resets its system smaller; the copies the
// rod makes of it every substep (its assembly cache) must then copy the small band, not the old one.
TEST(SymmetricBandedMatrix, ResetToFewerBlocksHoldsAndCopiesOnlyTheNewBand) {
  SymmetricBandedMatrix banded;
  banded.reset(16, 3, 3);
  ASSERT_EQ(banded.storedEntries(), 48u * 12u);
  banded.reset(4, 3, 3);
  EXPECT_EQ(banded.storedEntries(), 12u * 12u);
  banded.addScaledIdentity(3, 3, 2.0);
  const SymmetricBandedMatrix copy = banded;
  EXPECT_EQ(copy.storedEntries(), 12u * 12u);
  EXPECT_EQ(copy.entry(10, 10), 2.0);
  banded.reset(16, 3, 3);  // and grows back, zeroed
  EXPECT_EQ(banded.storedEntries(), 48u * 12u);
  for (int r = 0; r < banded.size(); ++r) EXPECT_EQ(banded.entry(r, r), 0.0);
}

}  // namespace
}  // namespace rope
