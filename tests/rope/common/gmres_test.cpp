// SPDX-License-Identifier: MIT
#include "rope/common/gmres.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/Dense>

namespace rope {
namespace {

GmresSolver::Product productOf(const Eigen::MatrixXd& a) {
  return [&a](const double* x, double* y) {
    Eigen::Map<Eigen::VectorXd>(y, a.rows()) = a * Eigen::Map<const Eigen::VectorXd>(x, a.cols());
  };
}

// I - mu theta V on a grid: V the lower-triangular integration (Volterra) operator, the linearised
// capstan relation between the sliding bounds round a support (bullet_bridge/contact/body_contacts.cpp).
// Its norm is about mu theta, far above 1, so fixed-point passes diverge; its spectrum is {1}.
Eigen::MatrixXd capstanOperator(int size, double muTheta) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(size, size);
  for (int i = 0; i < size; ++i)
    for (int j = 0; j < i; ++j) a(i, j) -= muTheta / size;
  return a;
}

TEST(Gmres, SolvesANonsymmetricSystemToTheTolerance) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const int size = 40;
  Eigen::MatrixXd a(size, size);
  for (int i = 0; i < size; ++i)
    for (int j = 0; j < size; ++j) a(i, j) = (i == j ? 4.0 : 0.0) + uniform(random);
  Eigen::VectorXd b(size);
  for (int i = 0; i < size; ++i) b(i) = uniform(random);
  const Eigen::VectorXd exact = a.partialPivLu().solve(b);
  Eigen::VectorXd x(size);
  GmresSolver solver;
  const GmresResult result = solver.solve(size, productOf(a), b.data(), x.data(), GmresSettings{size, 1e-12});
  ASSERT_TRUE(result.converged) << result.relativeResidual;
  EXPECT_LE((b - a * x).norm(), 1e-12 * b.norm());
  EXPECT_LE(result.relativeResidual, 1e-12);
  // The reported residual is the true one (to round-off), and so is the solution.
  EXPECT_NEAR(result.relativeResidual, (b - a * x).norm() / b.norm(), 1e-14);
  EXPECT_LE((x - exact).norm(), 1e-10 * exact.norm());
  EXPECT_LE(result.iterations, size);
}

// The capstan operator at mu theta = 2 pi (norm about 6): converged in few products, against the
// direct solve.
TEST(Gmres, SolvesTheCapstanOperatorInFewProducts) {
  const int size = 300;
  const Eigen::MatrixXd a = capstanOperator(size, 2.0 * 3.14159265358979323846);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(size);
  Eigen::VectorXd x(size);
  GmresSolver solver;
  const GmresResult result = solver.solve(size, productOf(a), b.data(), x.data(), GmresSettings{60, 1e-10});
  ASSERT_TRUE(result.converged) << result.relativeResidual << " after " << result.iterations;
  EXPECT_LE(result.iterations, 30);
  const Eigen::VectorXd exact = a.triangularView<Eigen::Lower>().solve(b);
  EXPECT_LE((x - exact).norm(), 1e-8 * exact.norm());
  // Fixed-point passes x <- b + (I - A) x grow instead: the case GMRES is here for.
  Eigen::VectorXd passes = Eigen::VectorXd::Zero(size);
  for (int pass = 0; pass < 6; ++pass) passes = b + (Eigen::MatrixXd::Identity(size, size) - a) * passes;
  EXPECT_GT((passes - exact).norm(), 0.1 * exact.norm());
}

// Stopped early, the iterate is the minimal-residual one of the Krylov space: the residual never
// grows with more products, and the reported figure is the true one.
TEST(Gmres, ResidualNeverGrowsWithMoreProducts) {
  const int size = 200;
  const Eigen::MatrixXd a = capstanOperator(size, 20.0);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(size, 1.0, -1.0);
  GmresSolver solver;
  double last = std::numeric_limits<double>::infinity();
  for (int products = 1; products <= 12; ++products) {
    Eigen::VectorXd x(size);
    const GmresResult result = solver.solve(size, productOf(a), b.data(), x.data(), GmresSettings{products, 1e-300});
    EXPECT_FALSE(result.converged);
    EXPECT_EQ(result.iterations, products);
    const double residual = (b - a * x).norm() / b.norm();
    EXPECT_NEAR(result.relativeResidual, residual, 1e-9 * std::max(1.0, residual)) << products;
    EXPECT_LE(residual, last * (1.0 + 1e-12)) << products;
    last = residual;
  }
}

TEST(Gmres, ZeroRightHandSideGivesZeroWithoutProducts) {
  const Eigen::MatrixXd a = capstanOperator(5, 1.0);
  const Eigen::VectorXd b = Eigen::VectorXd::Zero(5);
  Eigen::VectorXd x = Eigen::VectorXd::Constant(5, 3.0);
  GmresSolver solver;
  const GmresResult result = solver.solve(5, productOf(a), b.data(), x.data(), GmresSettings{});
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_EQ(x, Eigen::VectorXd::Zero(5));
}

// A product that turns non-finite stops the iteration: not converged, and x finite (the iterate of
// the products before it), so a caller can fall back without NaN reaching its state.
TEST(Gmres, NonFiniteProductStopsWithAFiniteIterate) {
  const Eigen::MatrixXd a = capstanOperator(20, 5.0);
  int calls = 0;
  const GmresSolver::Product poisoned = [&](const double* x, double* y) {
    productOf(a)(x, y);
    if (++calls == 3) y[4] = std::numeric_limits<double>::quiet_NaN();
  };
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(20);
  Eigen::VectorXd x(20);
  GmresSolver solver;
  const GmresResult result = solver.solve(20, poisoned, b.data(), x.data(), GmresSettings{20, 1e-14});
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.iterations, 3);
  EXPECT_TRUE(x.allFinite());
  EXPECT_LE((b - a * x).norm(), b.norm());  // two good products: no worse than x = 0
}

// One solver reused for systems of different sizes (the sliding samples change every pass).
TEST(Gmres, ReusedAcrossSizes) {
  GmresSolver solver;
  for (const int size : {30, 7, 120, 1}) {
    const Eigen::MatrixXd a = capstanOperator(size, 3.0);
    const Eigen::VectorXd b = Eigen::VectorXd::Ones(size);
    Eigen::VectorXd x(size);
    const GmresResult result = solver.solve(size, productOf(a), b.data(), x.data(), GmresSettings{size, 1e-12});
    EXPECT_TRUE(result.converged) << size;
    EXPECT_LE((b - a * x).norm(), 1e-11 * b.norm()) << size;
  }
}

}  // namespace
}  // namespace rope
