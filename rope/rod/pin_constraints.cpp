#include "rope/rod/pin_constraints.h"

#include <algorithm>
#include <cmath>

#include "rope/spline/bspline_basis.h"

namespace rope {

bool pinRowsIndependent(const KnotVector& knots, const std::vector<double>& sortedParameters) {
  const int d = knots.degree();
  int previous = -1;  // basis function matched to the previous pin
  BasisValues basis;
  for (const double s : sortedParameters) {
    const int k = knots.findSpan(s);
    evaluateBasis(knots, k, s, 0, basis);
    int matched = -1;
    for (int a = 0; a <= d && matched < 0; ++a) {
      const int i = k - d + a;
      if (i > previous && basis.d[0][static_cast<size_t>(a)] != 0.0) matched = i;
    }
    if (matched < 0) return false;
    previous = matched;
  }
  return true;
}

bool ConstrainedSolver::solve(const SymmetricBandedMatrix& factor, const std::vector<ConstraintRows>& rows,
                              double* x) {
  ready_ = false;
  const int size = factor.size();
  factor.forwardSubstitute(x, 0);  // y = L^-1 r
  const int columns = 3 * static_cast<int>(rows.size());
  columns_ = columns;
  if (columns == 0) {
    factor.backSubstitute(x);
    ready_ = true;
    return true;
  }
  const size_t total = static_cast<size_t>(columns) * static_cast<size_t>(size);
  if (z_.size() < total) z_.resize(total);
  start_.resize(static_cast<size_t>(columns));
  if (schur_.rows() != columns) {
    schur_.resize(columns, columns);
    lambda_.resize(columns);
  }
  for (int p = 0; p < static_cast<int>(rows.size()); ++p) {
    const ConstraintRows& row = rows[static_cast<size_t>(p)];
    for (int axis = 0; axis < 3; ++axis) {
      const int c = 3 * p + axis;
      double* z = &z_[static_cast<size_t>(c) * static_cast<size_t>(size)];
      const int begin = 3 * row.first + axis;
      start_[static_cast<size_t>(c)] = begin;
      std::fill(z + begin, z + size, 0.0);
      for (int a = 0; a < row.count; ++a) z[begin + 3 * a] = row.basis[a];
      factor.forwardSubstitute(z, begin);
    }
  }
  for (int r = 0; r < columns; ++r) {
    const double* zr = &z_[static_cast<size_t>(r) * static_cast<size_t>(size)];
    for (int c = 0; c <= r; ++c) {
      const double* zc = &z_[static_cast<size_t>(c) * static_cast<size_t>(size)];
      double sum = 0.0;
      for (int i = std::max(start_[static_cast<size_t>(r)], start_[static_cast<size_t>(c)]); i < size; ++i)
        sum += zr[i] * zc[i];
      schur_(r, c) = sum;
      schur_(c, r) = sum;
    }
    double projected = 0.0;
    for (int i = start_[static_cast<size_t>(r)]; i < size; ++i) projected += zr[i] * x[i];
    lambda_(r) = projected - rows[static_cast<size_t>(r / 3)].rhs[r % 3];
  }
  llt_.compute(schur_);
  if (llt_.info() != Eigen::Success) return false;
  // A nearly dependent pair of pins gives a tiny pivot and a huge lambda: treat as failure.
  const double smallest = llt_.matrixLLT().diagonal().minCoeff();
  const double largest = llt_.matrixLLT().diagonal().maxCoeff();
  if (!std::isfinite(smallest) || !std::isfinite(largest) || !(smallest > 1e-7 * largest)) return false;
  lambda_ = llt_.solve(lambda_);
  for (int r = 0; r < columns; ++r) {
    const double* zr = &z_[static_cast<size_t>(r) * static_cast<size_t>(size)];
    const double l = lambda_(r);
    for (int i = start_[static_cast<size_t>(r)]; i < size; ++i) x[i] -= zr[i] * l;
  }
  factor.backSubstitute(x);
  ready_ = true;
  return true;
}

void ConstrainedSolver::solveHomogeneous(const SymmetricBandedMatrix& factor, double* x, int firstRow) {
  const int size = factor.size();
  factor.forwardSubstitute(x, firstRow);
  if (columns_ > 0) {
    // lambda = (Z^T Z)^-1 Z^T y, the multipliers that keep G dv = 0.
    for (int r = 0; r < columns_; ++r) {
      const double* zr = &z_[static_cast<size_t>(r) * static_cast<size_t>(size)];
      double projected = 0.0;
      for (int i = std::max(start_[static_cast<size_t>(r)], firstRow); i < size; ++i) projected += zr[i] * x[i];
      lambda_(r) = projected;
    }
    lambda_ = llt_.solve(lambda_);
    for (int r = 0; r < columns_; ++r) {
      const double* zr = &z_[static_cast<size_t>(r) * static_cast<size_t>(size)];
      const double l = lambda_(r);
      for (int i = start_[static_cast<size_t>(r)]; i < size; ++i) x[i] -= zr[i] * l;
    }
  }
  factor.backSubstitute(x);
}

}  // namespace rope
