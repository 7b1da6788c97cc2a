// SPDX-License-Identifier: MIT
#include "rope/spline/bspline_basis.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <random>
#include <vector>

#include "tests/rope/spline/spline_test_support.h"

// Counts heap allocations so that the hot-path evaluation can be shown not to allocate. Under
// AddressSanitizer, which owns operator new itself, the count is not available.
#if defined(__SANITIZE_ADDRESS__)
#define SPLINEROPE_COUNT_ALLOCATIONS 0
#else
#define SPLINEROPE_COUNT_ALLOCATIONS 1
#endif

namespace {
std::atomic<long> allocationCount{0};
}  // namespace

#if SPLINEROPE_COUNT_ALLOCATIONS
// GCC pairs the replaced operator new with free() below and would warn about a mismatch that the
// replacement makes correct.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  allocationCount.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#endif

namespace rope {
namespace {

using test::expectInvalid;

TEST(BSplineBasis, MatchesTheRecursiveDefinition) {
  std::mt19937 rng(1);
  double worst = 0.0;
  for (int trial = 0; trial < 300; ++trial) {
    const int degree = 1 + trial % kMaxDegree;
    const KnotVector knots = test::randomKnots(rng, degree, degree + 1 + trial % 10, trial % 2 == 0, degree + 1);
    for (double s : test::sampleParameters(rng, knots, 20)) {
      const BasisValues basis = evaluateBasis(knots, s, 0);
      for (int i = 0; i < knots.controlPointCount(); ++i) {
        const double reference = test::referenceBasis(knots.values(), i, degree, s, knots.validEnd());
        const int j = i - basis.firstIndex();
        const double value = j >= 0 && j <= degree ? basis.d[0][static_cast<size_t>(j)] : 0.0;
        worst = std::max(worst, std::fabs(value - reference));
        ASSERT_EQ(basisFunction(knots, i, s), value);
      }
    }
  }
  EXPECT_LE(worst, 1e-14);
}

TEST(BSplineBasis, PartitionOfUnityAndNonNegativity) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 300; ++trial) {
    const int degree = 1 + trial % kMaxDegree;
    const KnotVector knots = test::randomKnots(rng, degree, degree + 1 + trial % 10, trial % 2 == 1, degree + 1);
    for (double s : test::sampleParameters(rng, knots, 20)) {
      const BasisValues basis = evaluateBasis(knots, s, 2);
      double sum = 0.0;
      double sum1 = 0.0;
      double sum2 = 0.0;
      double scale1 = 0.0;
      double scale2 = 0.0;
      for (int j = 0; j <= degree; ++j) {
        EXPECT_GE(basis.d[0][static_cast<size_t>(j)], 0.0);
        sum += basis.d[0][static_cast<size_t>(j)];
        sum1 += basis.d[1][static_cast<size_t>(j)];
        sum2 += basis.d[2][static_cast<size_t>(j)];
        scale1 += std::fabs(basis.d[1][static_cast<size_t>(j)]);
        scale2 += std::fabs(basis.d[2][static_cast<size_t>(j)]);
      }
      EXPECT_NEAR(sum, 1.0, 1e-14);
      EXPECT_LE(std::fabs(sum1), 1e-13 * (1.0 + scale1));  // derivatives of a constant vanish
      EXPECT_LE(std::fabs(sum2), 1e-13 * (1.0 + scale2));
      if (degree == 1) {
        for (int j = 0; j <= degree; ++j) EXPECT_EQ(basis.d[2][static_cast<size_t>(j)], 0.0);
      }
    }
  }
}

TEST(BSplineBasis, DerivativesAgreeWithCentralDifferences) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.1, 0.9);
  double worst1 = 0.0;
  double worst2 = 0.0;
  int checks = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int degree = 1 + trial % kMaxDegree;
    const KnotVector knots = test::randomKnots(rng, degree, degree + 1 + trial % 10, trial % 2 == 0, degree);
    for (int k = degree; k < knots.controlPointCount(); ++k) {
      const double a = knots[k];
      const double b = knots[k + 1];
      if (!(b > a)) continue;
      // Inside the span the functions are polynomials: central differences converge as h^2.
      const double s = a + (b - a) * unit(rng);
      // Central differences with Richardson extrapolation, (4 D(h/2) - D(h)) / 3: error O(h^4).
      const double h = 1e-3 * (b - a);
      BasisValues at;
      evaluateBasis(knots, k, s, 2, at);
      BasisValues shifted[4];  // s + h, s - h, s + h/2, s - h/2
      const double offsets[4] = {h, -h, 0.5 * h, -0.5 * h};
      for (int q = 0; q < 4; ++q) evaluateBasis(knots, k, s + offsets[q], 2, shifted[q]);
      for (int j = 0; j <= degree; ++j) {
        const size_t jj = static_cast<size_t>(j);
        auto richardson = [&](int order) {
          const double wide = (shifted[0].d[order][jj] - shifted[1].d[order][jj]) / (2 * h);
          const double narrow = (shifted[2].d[order][jj] - shifted[3].d[order][jj]) / h;
          return (4 * narrow - wide) / 3;
        };
        const double fd1 = richardson(0);
        const double fd2 = richardson(1);
        const double fd2Values = (shifted[0].d[0][jj] - 2 * at.d[0][jj] + shifted[1].d[0][jj]) / (h * h);
        // Scales: a derivative of order r is O(1 / span^r).
        const double h1 = b - a;
        worst1 = std::max(worst1, std::fabs(fd1 - at.d[1][jj]) * h1);
        worst2 = std::max(worst2, std::fabs(fd2 - at.d[2][jj]) * h1 * h1);
        // Plain second difference of the values: O(h^2) truncation, O(eps / h^2) rounding.
        EXPECT_LE(std::fabs(fd2Values - at.d[2][jj]) * h1 * h1, 1e-4);
        ++checks;
      }
    }
  }
  std::printf("basis derivative checks %d: max scaled |FD - C'| %.3g, |FD - C''| %.3g\n", checks, worst1, worst2);
  EXPECT_LE(worst1, 1e-9);
  EXPECT_LE(worst2, 1e-9);
}

TEST(BSplineBasis, HotPathDoesNotAllocate) {
  if (!SPLINEROPE_COUNT_ALLOCATIONS) GTEST_SKIP() << "allocation counting is off under AddressSanitizer";
  // The counter itself must see allocations, or the check below could not fail.
  const long probe = allocationCount.load();
  { std::vector<double> scratch(100, 1.0); }
  ASSERT_GT(allocationCount.load(), probe);
  const KnotVector knots = KnotVector::clampedUniform(5, 40);
  BasisValues basis;
  double sink = 0.0;
  const long before = allocationCount.load();
  for (int i = 0; i <= 1000; ++i) {
    const double s = i / 1000.0;
    evaluateBasis(knots, knots.findSpanUnchecked(s), s, 2, basis);
    sink += basis.d[2][0];
  }
  EXPECT_EQ(allocationCount.load(), before);
  EXPECT_TRUE(std::isfinite(sink));
}

// ---- bad input ----

TEST(BSplineBasisBadInput, ParameterOutsideRangeOrNonFinite) {
  const KnotVector knots = KnotVector::uniform(2, 5);  // valid [2, 5]
  expectInvalid([&] { evaluateBasis(knots, 5.5); }, "s", "5.5");
  expectInvalid([&] { evaluateBasis(knots, std::nan("")); }, "s", "nan");
  expectInvalid([&] { basisFunction(knots, 1, 1.0); }, "s", "1");
}

TEST(BSplineBasisBadInput, DerivativeOrderAndIndexOutOfRange) {
  const KnotVector knots = KnotVector::uniform(2, 5);
  expectInvalid([&] { evaluateBasis(knots, 3.0, 3); }, "derivatives", "3");
  expectInvalid([&] { evaluateBasis(knots, 3.0, -1); }, "derivatives", "-1");
  expectInvalid([&] { basisFunction(knots, 5, 3.0); }, "i", "5");
  expectInvalid([&] { basisFunction(knots, 0, 3.0, 4); }, "derivative", "4");
}

}  // namespace
}  // namespace rope
