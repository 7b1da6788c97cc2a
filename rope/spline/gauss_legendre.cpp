// SPDX-License-Identifier: MIT
#include "rope/spline/gauss_legendre.h"

#include <array>
#include <cmath>
#include <string>

#include "rope/common/error.h"

namespace rope {
namespace {

struct RuleTable {
  // nodes[n] and weights[n] hold the n-point rule in their first n entries.
  std::array<std::array<double, kMaxGaussPoints>, kMaxGaussPoints + 1> nodes{};
  std::array<std::array<double, kMaxGaussPoints>, kMaxGaussPoints + 1> weights{};

  RuleTable() {
    const double pi = std::acos(-1.0);
    for (int n = 1; n <= kMaxGaussPoints; ++n) {
      // Roots come in +-x pairs; find the non-negative ones, largest first, by Newton's method on
      // P_n from the three-term recurrence (k+1) P_{k+1} = (2k+1) x P_k - k P_{k-1}.
      for (int i = 0; i < (n + 1) / 2; ++i) {
        double x = std::cos(pi * (i + 0.75) / (n + 0.5));  // Tricomi's initial guess
        double derivative = 1.0;
        for (int iteration = 0; iteration < 100; ++iteration) {
          double p0 = 1.0;
          double p1 = x;
          for (int k = 1; k < n; ++k) {
            const double p2 = ((2.0 * k + 1.0) * x * p1 - k * p0) / (k + 1.0);
            p0 = p1;
            p1 = p2;
          }
          // P_n'(x) = n (x P_n - P_{n-1}) / (x^2 - 1); |x| < 1 strictly for every root.
          derivative = n * (x * p1 - p0) / (x * x - 1.0);
          const double step = p1 / derivative;
          x -= step;
          if (std::fabs(step) <= 1e-16) break;
        }
        // Recompute P_n' at the converged root for the weight 2 / ((1 - x^2) P_n'(x)^2).
        {
          double p0 = 1.0;
          double p1 = x;
          for (int k = 1; k < n; ++k) {
            const double p2 = ((2.0 * k + 1.0) * x * p1 - k * p0) / (k + 1.0);
            p0 = p1;
            p1 = p2;
          }
          derivative = n * (x * p1 - p0) / (x * x - 1.0);
        }
        const double weight = 2.0 / ((1.0 - x * x) * derivative * derivative);
        const size_t low = static_cast<size_t>(i);
        const size_t high = static_cast<size_t>(n - 1 - i);
        nodes[static_cast<size_t>(n)][low] = -x;
        nodes[static_cast<size_t>(n)][high] = x;
        weights[static_cast<size_t>(n)][low] = weight;
        weights[static_cast<size_t>(n)][high] = weight;
      }
      // The middle root of an odd rule is exactly 0.
      if (n % 2 == 1) nodes[static_cast<size_t>(n)][static_cast<size_t>(n / 2)] = 0.0;
    }
  }
};

const RuleTable& table() {
  static const RuleTable rules;  // thread-safe one-time initialisation (C++11 magic statics)
  return rules;
}

}  // namespace

GaussRule gaussLegendre(int count) {
  if (count < 1 || count > kMaxGaussPoints) {
    throw InvalidArgument("count", std::to_string(count), "must be in 1.." + std::to_string(kMaxGaussPoints));
  }
  const RuleTable& rules = table();
  GaussRule rule;
  rule.count = count;
  rule.nodes = rules.nodes[static_cast<size_t>(count)].data();
  rule.weights = rules.weights[static_cast<size_t>(count)].data();
  return rule;
}

}  // namespace rope
