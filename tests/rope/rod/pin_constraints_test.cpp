// SPDX-License-Identifier: MIT
#include "rope/rod/pin_constraints.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <random>

#include "rope/spline/bspline_curve.h"

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

// The rows as dense gradients over the n unknowns (one per row) and their right-hand sides.
void denseRows(const std::vector<ConstraintRows>& rows, int n, std::vector<Eigen::VectorXd>& gradients,
               std::vector<double>& values) {
  for (const ConstraintRows& c : rows) {
    for (int k = 0; k < c.rowCount; ++k) {
      Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
      for (int a = 0; a < c.count; ++a)
        for (int axis = 0; axis < 3; ++axis) g(3 * (c.first + a) + axis) = c.basis[a] * c.directions[k][axis];
      gradients.push_back(g);
      values.push_back(c.rhs[k]);
    }
  }
}

// Solves S x = r - G^T lambda, G x = c with the banded solver and checks it against the dense KKT
// system, the rows' values and (homogeneous form) G y = 0.
void checkAgainstDenseKkt(const std::vector<ConstraintRows>& rows) {
  SymmetricBandedMatrix banded;
  const Eigen::MatrixXd S = makeSystem(14, 3, banded);
  const int n = static_cast<int>(S.rows());
  const Eigen::VectorXd r = Eigen::VectorXd::LinSpaced(n, -1.0, 1.0);
  std::vector<Eigen::VectorXd> gradients;
  std::vector<double> values;
  denseRows(rows, n, gradients, values);
  const int m = static_cast<int>(gradients.size());
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n + m, n + m);
  Eigen::VectorXd rhs(n + m);
  kkt.topLeftCorner(n, n) = S;
  rhs.head(n) = r;
  for (int k = 0; k < m; ++k) {
    kkt.block(n + k, 0, 1, n) = gradients[static_cast<size_t>(k)].transpose();
    kkt.block(0, n + k, n, 1) = gradients[static_cast<size_t>(k)];
    rhs(n + k) = values[static_cast<size_t>(k)];
  }
  const Eigen::VectorXd expected = kkt.fullPivLu().solve(rhs).head(n);
  ASSERT_TRUE(banded.factorize());
  ConstrainedSolver solver;
  Eigen::VectorXd x = r;
  ASSERT_TRUE(solver.solve(banded, rows, x.data()));
  EXPECT_LT((x - expected).norm(), 1e-12 * expected.norm());
  for (int k = 0; k < m; ++k) {
    EXPECT_NEAR(gradients[static_cast<size_t>(k)].dot(x), values[static_cast<size_t>(k)], 1e-12);
  }
  Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(n, 0.5, -2.0);
  solver.solveHomogeneous(banded, y.data());
  for (int k = 0; k < m; ++k) EXPECT_NEAR(gradients[static_cast<size_t>(k)].dot(y), 0.0, 1e-12);
  // Without constraints it is the plain solve.
  Eigen::VectorXd z = r;
  ASSERT_TRUE(solver.solve(banded, {}, z.data()));
  EXPECT_LT((z - S.ldlt().solve(r)).norm(), 1e-12 * z.norm());
}

TEST(ConstrainedSolver, MatchesTheDenseKktSolution) {
  checkAgainstDenseKkt({row(0, {1.0, 0.0, 0.0, 0.0}, Vec3(0.1, -0.2, 0.3)),
                        row(5, {0.1, 0.5, 0.3, 0.1}, Vec3(1.0, 2.0, -1.0)),
                        row(10, {0.0, 0.0, 0.0, 1.0}, Vec3(-0.5, 0.0, 0.25))});
}

// Three right-hand sides solved together (a contact point's impulse responses) are each the one-column
// homogeneous solve, bit for bit, with constraint columns that share passes (a pin's three rows) and
// ones that do not.
TEST(ConstrainedSolver, ThreeColumnHomogeneousSolvesAreTheOneColumnOnes) {
  SymmetricBandedMatrix banded;
  const Eigen::MatrixXd S = makeSystem(14, 3, banded);
  const int n = static_cast<int>(S.rows());
  ASSERT_TRUE(banded.factorize());
  ConstraintRows clamp = row(0, {0.0, 0.7, 0.2, 0.1}, Vec3::Zero());
  clamp.rowCount = 2;
  clamp.directions[0] = Vec3(0.0, 0.6, 0.8);
  clamp.directions[1] = Vec3(1.0, 0.0, 0.0);
  const std::vector<ConstraintRows> rows = {row(0, {1.0, 0.0, 0.0, 0.0}, Vec3(0.1, -0.2, 0.3)), clamp,
                                            row(10, {0.0, 0.0, 0.0, 1.0}, Vec3(-0.5, 0.0, 0.25))};
  ConstrainedSolver solver;
  Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, -1.0, 1.0);
  ASSERT_TRUE(solver.solve(banded, rows, x.data()));
  std::vector<Eigen::VectorXd> gradients;
  std::vector<double> values;
  denseRows(rows, n, gradients, values);
  for (const int firstRow : {0, 4, 21}) {
    Eigen::MatrixXd columns = Eigen::MatrixXd::Zero(n, 3);
    for (int c = 0; c < 3; ++c)
      for (int r = firstRow; r < firstRow + 6; ++r) columns(r, c) = std::sin(2.0 + r + 3.0 * c);
    Eigen::MatrixXd single = columns;
    for (int c = 0; c < 3; ++c) solver.solveHomogeneous(banded, single.col(c).data(), firstRow);
    Eigen::MatrixXd together = columns;
    solver.solveHomogeneous3(banded, together.data(), firstRow);
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < n; ++r) EXPECT_EQ(together(r, c), single(r, c)) << "firstRow " << firstRow << " column " << c << " row " << r;
      for (const Eigen::VectorXd& g : gradients) EXPECT_NEAR(g.dot(together.col(c)), 0.0, 1e-12);
    }
    // Onward (a response read only at rows from its own load on): the same bits on those rows.
    Eigen::MatrixXd onward = columns;
    solver.solveHomogeneous3(banded, onward.data(), firstRow, firstRow);
    for (int c = 0; c < 3; ++c)
      for (int r = firstRow; r < n; ++r) EXPECT_EQ(onward(r, c), single(r, c)) << "onward from " << firstRow << " column " << c << " row " << r;
  }
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

TEST(ConstrainedSolver, DirectionalRowsMatchTheDenseKktSolution) {
  // Pins (three axis rows) mixed with clamp-style rows along arbitrary directions (two per block).
  std::vector<ConstraintRows> rows = {row(0, {1.0, 0.0, 0.0, 0.0}, Vec3(0.1, -0.2, 0.3)),
                                      row(6, {-0.9, 0.3, 0.5, 0.1}, Vec3(0.4, -1.0, 0.0)),
                                      row(10, {0.0, 0.0, 0.0, 1.0}, Vec3(-0.5, 0.0, 0.25)),
                                      row(10, {0.0, 0.0, -3.0, 3.0}, Vec3(0.7, 0.2, 0.0))};
  for (int i : {1, 3}) {
    const Vec3 d = i == 1 ? Vec3(0.3, -0.5, 0.8).normalized() : Vec3::UnitZ();
    orthonormalComplement(d, rows[static_cast<size_t>(i)].directions[0], rows[static_cast<size_t>(i)].directions[1]);
    rows[static_cast<size_t>(i)].rowCount = 2;
  }
  checkAgainstDenseKkt(rows);
}

TEST(ConstraintRows, OrthonormalComplementIsRightHandedAndDeterministic) {
  for (const Vec3& d : {Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0.3, -0.5, 0.8).normalized(),
                        Vec3(1, 1e-17, -1e-17).normalized()}) {
    Vec3 e1, e2;
    orthonormalComplement(d, e1, e2);
    EXPECT_NEAR(e1.norm(), 1.0, 1e-15);
    EXPECT_NEAR(e2.norm(), 1.0, 1e-15);
    EXPECT_NEAR(e1.dot(d), 0.0, 1e-15);
    EXPECT_NEAR(e2.dot(d), 0.0, 1e-15);
    EXPECT_NEAR(e1.dot(e2), 0.0, 1e-15);
    EXPECT_NEAR(e1.cross(e2).dot(d), 1.0, 1e-15);
  }
}

// The rows are the Jacobian of the constraint functions g(q) = C(s) (pin) and g_k(q) = span e_k . C'(s)
// (clamp), which are linear in q: central differences are exact up to rounding. Their right-hand
// side makes the end-of-step positions q + h (v + dv) satisfy g = target (pin) or g = 0 (clamp):
// G dv - c = (g(q + h (v + dv)) - g_target) / h for any dv.
TEST(ConstraintRows, PinAndClampRowsAreTheJacobianOfTheirConstraints) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const KnotVector knots = KnotVector::clampedUniform(3, 9, 0.0, 2.0);
  PointList q(9), v(9), dv(9);
  for (int i = 0; i < 9; ++i) {
    q[static_cast<size_t>(i)] = Vec3(0.25 * i, 0.1 * uniform(rng), 0.1 * uniform(rng));
    v[static_cast<size_t>(i)] = Vec3(uniform(rng), uniform(rng), uniform(rng));
    dv[static_cast<size_t>(i)] = Vec3(uniform(rng), uniform(rng), uniform(rng));
  }
  const double h = 1.0 / 60;
  const Vec3 direction = Vec3(0.9, 0.3, -0.2).normalized();
  const Vec3 target(0.7, 0.05, -0.02);
  for (double s : {0.0, 0.37, 1.0, 1.61, 2.0}) {
    const ConstraintRows pin = pinRows(knots, q, v, s, target, h);
    const ConstraintRows tangent = clampTangentRows(knots, q, v, s, direction, h);
    EXPECT_EQ(pin.rowCount, 3);
    EXPECT_EQ(tangent.rowCount, 2);
    const int k = knots.findSpan(s);
    const double span = knots[k + 1] - knots[k];
    auto pinValue = [&](const PointList& points, int row) { return evaluateCurve(knots, points, s).position[row]; };
    auto tangentValue = [&](const PointList& points, int row) {
      return span * tangent.directions[row].dot(evaluateCurve(knots, points, s).firstDerivative);
    };
    for (int i = 0; i < 9; ++i) {
      for (int axis = 0; axis < 3; ++axis) {
        PointList plus = q, minus = q;
        const double eps = 1e-6;
        plus[static_cast<size_t>(i)][axis] += eps;
        minus[static_cast<size_t>(i)][axis] -= eps;
        auto coefficient = [&](const ConstraintRows& rows, int row) {
          const int a = i - rows.first;
          return a >= 0 && a < rows.count ? rows.basis[a] * rows.directions[row][axis] : 0.0;
        };
        for (int row = 0; row < 3; ++row) {
          const double fd = (pinValue(plus, row) - pinValue(minus, row)) / (2 * eps);
          EXPECT_NEAR(coefficient(pin, row), fd, 1e-9) << "pin s " << s << " point " << i << " axis " << axis;
        }
        for (int row = 0; row < 2; ++row) {
          const double fd = (tangentValue(plus, row) - tangentValue(minus, row)) / (2 * eps);
          EXPECT_NEAR(coefficient(tangent, row), fd, 1e-8) << "clamp s " << s << " point " << i << " axis " << axis;
        }
      }
    }
    PointList after(9);
    for (size_t i = 0; i < 9; ++i) after[i] = q[i] + h * (v[i] + dv[i]);
    for (int row = 0; row < 3; ++row) {
      double g = 0.0;
      for (int a = 0; a < pin.count; ++a) g += pin.basis[a] * dv[static_cast<size_t>(pin.first + a)][row];
      EXPECT_NEAR(g - pin.rhs[row], (pinValue(after, row) - target[row]) / h, 1e-10);
    }
    for (int row = 0; row < 2; ++row) {
      double g = 0.0;
      for (int a = 0; a < tangent.count; ++a) {
        g += tangent.basis[a] * tangent.directions[row].dot(dv[static_cast<size_t>(tangent.first + a)]);
      }
      EXPECT_NEAR(g - tangent.rhs[row], tangentValue(after, row) / h, 1e-10);
    }
  }
}

}  // namespace
}  // namespace rope
