// SPDX-License-Identifier: MIT
#include "rope/spline/bspline_basis.h"

#include <string>

#include "rope/common/error.h"

namespace rope {
namespace {

static_assert(kMaxDegree == 5, "evaluateBasis dispatches degrees 1..5");

// Cox–de Boor in the triangular form of Piegl & Tiller A2.2, keeping the rows of degree d-1 and d-2,
// from which the derivatives follow by N'_{i,p} = p (N_{i,p-1}/(s_{i+p}-s_i) - N_{i+1,p-1}/(s_{i+p+1}-s_{i+1})).
// Step j of the recursion divides by s_{k+r+1} - s_{k+1-j+r} (r = 0..j-1), and the derivative formulas
// divide by exactly the differences of steps d and d-1. All are knot differences across the
// non-empty span k, so they are > 0; their reciprocals are taken up front, independent of each
// other, so the divisions overlap instead of forming a chain through the recursion.
// The degree is a template parameter so that every loop below has a fixed trip count and unrolls.
template <int d>
void evaluateBasisOfDegree(const double* t, double s, int derivatives, BasisValues& out) {
  double inverse[kMaxDegree + 1][kMaxDegree];  // inverse[j][r] = 1 / (s_{k+r+1} - s_{k+1-j+r})
  for (int j = 1; j <= d; ++j) {
    for (int r = 0; r < j; ++r) inverse[j][r] = 1.0 / (t[r + 1] - t[1 - j + r]);
  }
  double left[kMaxDegree + 1];
  double right[kMaxDegree + 1];
  for (int j = 1; j <= d; ++j) {
    left[j] = s - t[1 - j];
    right[j] = t[j] - s;
  }
  double n[kMaxDegree + 1];
  double rowD1[kMaxDegree + 1];  // N_{k-d+1+j, d-1} / (s_{k+1+j} - s_{k-d+1+j}), j = 0..d-1
  double rowD2[kMaxDegree + 1];  // N_{k-d+2+j, d-2} / (s_{k+1+j} - s_{k-d+2+j}), j = 0..d-2
  n[0] = 1.0;
  for (int j = 1; j <= d; ++j) {
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = n[r] * inverse[j][r];
      if (j == d) rowD1[r] = temp;
      if (j == d - 1) rowD2[r] = temp;
      n[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    n[j] = saved;
  }
  for (int j = 0; j <= d; ++j) out.d[0][static_cast<size_t>(j)] = n[j];
  if (derivatives < 1) {
    for (int order = 1; order <= kMaxBasisDerivative; ++order) out.d[static_cast<size_t>(order)].fill(0.0);
    return;
  }

  const double p = static_cast<double>(d);
  {
    double previous = 0.0;
    for (int j = 0; j < d; ++j) {
      const double term = p * rowD1[j];
      out.d[1][static_cast<size_t>(j)] = previous - term;
      previous = term;
    }
    out.d[1][static_cast<size_t>(d)] = previous;
  }
  if (derivatives < 2 || d < 2) {
    out.d[2].fill(0.0);
    return;
  }

  // Derivatives of the degree d-1 functions from the degree d-2 row, then the same step again.
  double rowD1Derivative[kMaxDegree];
  {
    const double q = static_cast<double>(d - 1);
    double previous = 0.0;
    for (int j = 0; j < d - 1; ++j) {
      const double term = q * rowD2[j];
      rowD1Derivative[j] = previous - term;
      previous = term;
    }
    rowD1Derivative[d - 1] = previous;
  }
  double previous = 0.0;
  for (int j = 0; j < d; ++j) {
    const double term = p * rowD1Derivative[j] * inverse[d][j];
    out.d[2][static_cast<size_t>(j)] = previous - term;
    previous = term;
  }
  out.d[2][static_cast<size_t>(d)] = previous;
}

}  // namespace

void evaluateBasis(const KnotVector& knots, int span, double s, int derivatives, BasisValues& out) {
  const double* t = knots.values().data() + span;  // t[i] = s_{k+i}
  out.span = span;
  out.degree = knots.degree();
  switch (knots.degree()) {
    case 1: evaluateBasisOfDegree<1>(t, s, derivatives, out); break;
    case 2: evaluateBasisOfDegree<2>(t, s, derivatives, out); break;
    case 3: evaluateBasisOfDegree<3>(t, s, derivatives, out); break;
    case 4: evaluateBasisOfDegree<4>(t, s, derivatives, out); break;
    default: evaluateBasisOfDegree<kMaxDegree>(t, s, derivatives, out); break;
  }
}

BasisValues evaluateBasis(const KnotVector& knots, double s, int derivatives) {
  if (derivatives < 0 || derivatives > kMaxBasisDerivative) {
    throw InvalidArgument("derivatives", std::to_string(derivatives),
                          "must be in 0.." + std::to_string(kMaxBasisDerivative));
  }
  const int span = knots.findSpan(s);
  BasisValues values;
  evaluateBasis(knots, span, s, derivatives, values);
  return values;
}

double basisFunction(const KnotVector& knots, int i, double s, int derivative) {
  if (i < 0 || i >= knots.controlPointCount()) {
    throw InvalidArgument("i", std::to_string(i),
                          "must be in 0.." + std::to_string(knots.controlPointCount() - 1));
  }
  if (derivative < 0 || derivative > kMaxBasisDerivative) {
    throw InvalidArgument("derivative", std::to_string(derivative),
                          "must be in 0.." + std::to_string(kMaxBasisDerivative));
  }
  const BasisValues values = evaluateBasis(knots, s, derivative);
  const int j = i - values.firstIndex();
  if (j < 0 || j > values.degree) return 0.0;
  return values.d[static_cast<size_t>(derivative)][static_cast<size_t>(j)];
}

}  // namespace rope
