#include "rope/spline/bspline_basis.h"

#include <string>

#include "rope/common/error.h"

namespace rope {

// Cox–de Boor in the triangular form of Piegl & Tiller A2.2, keeping the rows of degree d-1 and d-2,
// from which the derivatives follow by N'_{i,p} = p (N_{i,p-1}/(s_{i+p}-s_i) - N_{i+1,p-1}/(s_{i+p+1}-s_{i+1})).
// Every denominator below is a difference of knots on both sides of the non-empty span k, so it is > 0.
void evaluateBasis(const KnotVector& knots, int span, double s, int derivatives, BasisValues& out) {
  const int d = knots.degree();
  const double* t = knots.values().data();
  out.span = span;
  out.degree = d;

  double left[kMaxDegree + 1];
  double right[kMaxDegree + 1];
  double n[kMaxDegree + 1];
  double rowD1[kMaxDegree + 1];  // N_{k-d+1+j, d-1}, j = 0..d-1
  double rowD2[kMaxDegree + 1];  // N_{k-d+2+j, d-2}, j = 0..d-2
  n[0] = 1.0;
  for (int j = 1; j <= d; ++j) {
    if (j == d - 1) {
      for (int r = 0; r < j; ++r) rowD2[r] = n[r];
    }
    if (j == d) {
      for (int r = 0; r < j; ++r) rowD1[r] = n[r];
    }
    left[j] = s - t[span + 1 - j];
    right[j] = t[span + j] - s;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = n[r] / (right[r + 1] + left[j - r]);
      n[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    n[j] = saved;
  }
  for (int j = 0; j <= d; ++j) out.d[0][static_cast<size_t>(j)] = n[j];
  for (int order = 1; order <= kMaxBasisDerivative; ++order) {
    for (int j = 0; j <= d; ++j) out.d[static_cast<size_t>(order)][static_cast<size_t>(j)] = 0.0;
  }
  if (derivatives < 1) return;

  // d / (s_{k+1+m} - s_{k-d+1+m}), m = 0..d-1: d over the support length of N_{k-d+1+m, d-1}.
  double scale[kMaxDegree];
  for (int m = 0; m < d; ++m) scale[m] = static_cast<double>(d) / (t[span + 1 + m] - t[span - d + 1 + m]);
  {
    double previous = 0.0;
    for (int j = 0; j < d; ++j) {
      const double term = rowD1[j] * scale[j];
      out.d[1][static_cast<size_t>(j)] = previous - term;
      previous = term;
    }
    out.d[1][static_cast<size_t>(d)] = previous;
  }
  if (derivatives < 2 || d < 2) return;

  // Derivatives of the degree d-1 functions from the degree d-2 row, then the same step again.
  double rowD1Derivative[kMaxDegree];
  {
    const double p = static_cast<double>(d - 1);
    double previous = 0.0;
    for (int j = 0; j < d - 1; ++j) {
      const double term = p * rowD2[j] / (t[span + 1 + j] - t[span - d + 2 + j]);
      rowD1Derivative[j] = previous - term;
      previous = term;
    }
    rowD1Derivative[d - 1] = previous;
  }
  double previous = 0.0;
  for (int j = 0; j < d; ++j) {
    const double term = rowD1Derivative[j] * scale[j];
    out.d[2][static_cast<size_t>(j)] = previous - term;
    previous = term;
  }
  out.d[2][static_cast<size_t>(d)] = previous;
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
