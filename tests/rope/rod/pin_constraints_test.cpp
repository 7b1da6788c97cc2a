#include "rope/rod/pin_constraints.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

namespace rope {
namespace {

// Random SPD 3x3-block banded system, filled in both forms.
Eigen::MatrixXd makeSystem(int blocks, int d, SymmetricBandedMatrix& banded) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  banded.reset(blocks, 3, d);
  const int n = banded.size();
  const int w = banded.halfBandwidth();
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  for (int r = 0; r < n; ++r) {
    for (int c = std::max(0, r - w); c < r; ++c) {
      const double v = uniform(rng);
      banded.at(r, c) = v;
      dense(r, c) = dense(c, r) = v;
    }
    banded.at(r, r) = dense(r, r) = 2.0 * w + 2.0;
  }
  return dense;
}

ConstraintRows row(int first, std::vector<double> basis, const Vec3& rhs) {
  ConstraintRows r;
  r.first = first;
  r.count = static_cast<int>(basis.size());
  for (size_t a = 0; a < basis.size(); ++a) r.basis[a] = basis[a];
  r.rhs = rhs;
  return r;
}

TEST(ConstrainedSolver, MatchesTheDenseKktSolution) {
  SymmetricBandedMatrix banded;
  const int blocks = 14;
  const Eigen::MatrixXd S = makeSystem(blocks, 3, banded);
  const int n = static_cast<int>(S.rows());
  std::vector<ConstraintRows> rows = {row(0, {1.0, 0.0, 0.0, 0.0}, Vec3(0.1, -0.2, 0.3)),
                                      row(5, {0.1, 0.5, 0.3, 0.1}, Vec3(1.0, 2.0, -1.0)),
                                      row(10, {0.0, 0.0, 0.0, 1.0}, Vec3(-0.5, 0.0, 0.25))};
  Eigen::VectorXd r = Eigen::VectorXd::LinSpaced(n, -1.0, 1.0);
  // Dense KKT reference.
  const int m = 3 * static_cast<int>(rows.size());
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n + m, n + m);
  Eigen::VectorXd rhs(n + m);
  kkt.topLeftCorner(n, n) = S;
  rhs.head(n) = r;
  for (int p = 0; p < static_cast<int>(rows.size()); ++p)
    for (int axis = 0; axis < 3; ++axis) {
      const ConstraintRows& c = rows[static_cast<size_t>(p)];
      for (int a = 0; a < c.count; ++a) {
        kkt(n + 3 * p + axis, 3 * (c.first + a) + axis) = c.basis[a];
        kkt(3 * (c.first + a) + axis, n + 3 * p + axis) = c.basis[a];
      }
      rhs(n + 3 * p + axis) = c.rhs[axis];
    }
  const Eigen::VectorXd expected = kkt.fullPivLu().solve(rhs).head(n);
  ASSERT_TRUE(banded.factorize());
  ConstrainedSolver solver;
  Eigen::VectorXd x = r;
  ASSERT_TRUE(solver.solve(banded, rows, x.data()));
  EXPECT_LT((x - expected).norm(), 1e-12 * expected.norm());
  // The constraints hold.
  for (const ConstraintRows& c : rows) {
    Vec3 value = Vec3::Zero();
    for (int a = 0; a < c.count; ++a) value += c.basis[a] * Vec3(x(3 * (c.first + a)), x(3 * (c.first + a) + 1), x(3 * (c.first + a) + 2));
    EXPECT_LT((value - c.rhs).norm(), 1e-12);
  }
  // Without constraints it is the plain solve.
  Eigen::VectorXd y = r;
  ASSERT_TRUE(solver.solve(banded, {}, y.data()));
  EXPECT_LT((y - S.ldlt().solve(r)).norm(), 1e-12 * y.norm());
}

TEST(ConstrainedSolver, DependentConstraintsAreReported) {
  SymmetricBandedMatrix banded;
  makeSystem(8, 3, banded);
  ASSERT_TRUE(banded.factorize());
  const ConstraintRows a = row(2, {0.2, 0.3, 0.4, 0.1}, Vec3(1, 1, 1));
  ConstrainedSolver solver;
  std::vector<double> x(static_cast<size_t>(banded.size()), 1.0);
  EXPECT_FALSE(solver.solve(banded, {a, a}, x.data()));
}

}  // namespace
}  // namespace rope
