// SPDX-License-Identifier: MIT
#pragma once
// B-spline basis functions by the Cox–de Boor recursion ([A] §3.1; Piegl & Tiller A2.2/A2.3).
// On span k only the d+1 functions b_{k-d}, ..., b_k are non-zero (locality), so every evaluation
// works on d+1 values and costs O(d^2), independent of the number of control points.

#include <array>

#include "rope/spline/knot_vector.h"

namespace rope {

// Highest derivative order evaluated (C'' is what the rod's bending energy needs).
constexpr int kMaxBasisDerivative = 2;

struct BasisValues {
  int span = 0;    // k: entry j belongs to basis function b_{k-d+j}
  int degree = 0;
  // d[order][j] = d^order b_{k-d+j} / ds^order at s; orders above the requested one are zero.
  std::array<std::array<double, kMaxDegree + 1>, kMaxBasisDerivative + 1> d{};
  int firstIndex() const { return span - degree; }
};

// Hot-path form: span must be findSpan(s) and 0 <= derivatives <= kMaxBasisDerivative; no checks,
// no allocation.
void evaluateBasis(const KnotVector& knots, int span, double s, int derivatives, BasisValues& out);

// Validating form: throws InvalidArgument for s outside the valid range or NaN ("s"), or derivatives
// outside 0..kMaxBasisDerivative ("derivatives").
BasisValues evaluateBasis(const KnotVector& knots, double s, int derivatives = kMaxBasisDerivative);

// Value of the single basis function b_i (or its derivative) at s, zero outside its support.
// For tests and set-up code, not inner loops. Throws for i out of range, s outside the valid range.
double basisFunction(const KnotVector& knots, int i, double s, int derivative = 0);

}  // namespace rope
