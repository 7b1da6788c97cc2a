// SPDX-License-Identifier: MIT
#include "rope/spline/gauss_legendre.h"

#include <gtest/gtest.h>

#include <cmath>
#include <thread>
#include <vector>

#include "tests/rope/spline/spline_test_support.h"

namespace rope {
namespace {

using test::expectInvalid;

double integratePower(const GaussRule& rule, int power) {
  double sum = 0.0;
  for (int i = 0; i < rule.count; ++i) sum += rule.weights[i] * std::pow(rule.nodes[i], power);
  return sum;
}

double exactPower(int power) { return power % 2 == 1 ? 0.0 : 2.0 / (power + 1); }

TEST(GaussLegendre, IntegratesPolynomialsOfDegreeTwoNMinusOneExactly) {
  for (int n = 1; n <= kMaxGaussPoints; ++n) {
    const GaussRule rule = gaussLegendre(n);
    ASSERT_EQ(rule.count, n);
    for (int power = 0; power <= 2 * n - 1; ++power) {
      EXPECT_NEAR(integratePower(rule, power), exactPower(power), 4e-15) << "n " << n << " x^" << power;
    }
  }
}

TEST(GaussLegendre, ErrorForDegreeTwoNIsTheTheoreticalOne) {
  // The rules are exact to degree 2n-1 and no further: for x^{2n} the error is
  // 2^{2n+1} (n!)^4 / ((2n+1) ((2n)!)^2) (the Gauss remainder with f^{(2n)} = (2n)!).
  for (int n = 1; n <= 12; ++n) {
    const GaussRule rule = gaussLegendre(n);
    const double nFactorial = std::tgamma(n + 1.0);
    const double twoNFactorial = std::tgamma(2.0 * n + 1.0);
    const double expected = std::pow(2.0, 2 * n + 1) * std::pow(nFactorial, 4) / ((2 * n + 1) * twoNFactorial * twoNFactorial);
    const double error = exactPower(2 * n) - integratePower(rule, 2 * n);
    EXPECT_NEAR(error, expected, 1e-13 + 1e-10 * expected) << "n " << n;
    EXPECT_GT(error, 1e-12);
  }
}

TEST(GaussLegendre, WeightsSumToTwoAndNodesAreSymmetricAndSorted) {
  for (int n = 1; n <= kMaxGaussPoints; ++n) {
    const GaussRule rule = gaussLegendre(n);
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      sum += rule.weights[i];
      EXPECT_GT(rule.weights[i], 0.0);
      EXPECT_GT(rule.nodes[i], -1.0);
      EXPECT_LT(rule.nodes[i], 1.0);
      if (i > 0) {
        EXPECT_LT(rule.nodes[i - 1], rule.nodes[i]);
      }
      EXPECT_EQ(rule.nodes[i], -rule.nodes[n - 1 - i]);
      EXPECT_EQ(rule.weights[i], rule.weights[n - 1 - i]);
    }
    EXPECT_NEAR(sum, 2.0, 2e-15) << "n " << n;
  }
}

TEST(GaussLegendre, ThreePointRuleHasTheClosedForm) {
  const GaussRule rule = gaussLegendre(3);
  EXPECT_NEAR(rule.nodes[0], -std::sqrt(0.6), 4e-16);
  EXPECT_EQ(rule.nodes[1], 0.0);
  EXPECT_NEAR(rule.weights[0], 5.0 / 9.0, 4e-16);
  EXPECT_NEAR(rule.weights[1], 8.0 / 9.0, 4e-16);
}

TEST(GaussLegendre, SharedRulesAreStableAcrossCallsAndThreads) {
  const GaussRule first = gaussLegendre(16);
  std::vector<const double*> seen(4, nullptr);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) threads.emplace_back([&seen, t] { seen[static_cast<size_t>(t)] = gaussLegendre(16).nodes; });
  for (std::thread& thread : threads) thread.join();
  for (const double* nodes : seen) EXPECT_EQ(nodes, first.nodes);
}

TEST(GaussLegendreBadInput, CountOutOfRange) {
  expectInvalid([] { gaussLegendre(0); }, "count", "0");
  expectInvalid([] { gaussLegendre(kMaxGaussPoints + 1); }, "count", "33");
}

}  // namespace
}  // namespace rope
