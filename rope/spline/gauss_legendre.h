// SPDX-License-Identifier: MIT
#pragma once
// Gauss–Legendre quadrature rules on [-1, 1]. An n-point rule integrates polynomials of degree
// 2n-1 exactly; the rod's integrals (docs/method.md §7) pick n from the polynomial degree of their integrand.

namespace rope {

constexpr int kMaxGaussPoints = 32;

struct GaussRule {
  int count = 0;
  const double* nodes = nullptr;    // ascending, in (-1, 1)
  const double* weights = nullptr;  // sum to 2
};

// Rules are computed once (Newton on the Legendre recurrence, to machine precision) and shared;
// thread-safe, no allocation after the first call. Throws InvalidArgument("count", ...) outside
// 1..kMaxGaussPoints.
GaussRule gaussLegendre(int count);

}  // namespace rope
