// SPDX-License-Identifier: MIT
#include "rope/rod/pin_constraints.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "rope/spline/bspline_basis.h"

namespace rope {

ConstraintRows pinRows(const KnotVector& knots, const PointList& points, const PointList& velocities, double s,
                       const Vec3& target, double h) {
  const int d = knots.degree();
  const int k = knots.findSpan(s);
  BasisValues basis;
  evaluateBasis(knots, k, s, 0, basis);
  ConstraintRows row;
  row.first = k - d;
  row.count = d + 1;
  Vec3 position = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
  for (int a = 0; a <= d; ++a) {
    row.basis[a] = basis.d[0][static_cast<size_t>(a)];
    position += row.basis[a] * points[static_cast<size_t>(row.first + a)];
    velocity += row.basis[a] * velocities[static_cast<size_t>(row.first + a)];
  }
  row.rhs = (target - position) / h - velocity;
  return row;
}

void orthonormalComplement(const Vec3& direction, Vec3& e1, Vec3& e2) {
  // Cross with the axis least aligned with the direction: never close to parallel.
  int axis = 0;
  for (int c = 1; c < 3; ++c)
    if (std::fabs(direction[c]) < std::fabs(direction[axis])) axis = c;
  e1 = direction.cross(Vec3::Unit(axis)).normalized();
  e2 = direction.cross(e1);
}

ConstraintRows clampTangentRows(const KnotVector& knots, const PointList& points, const PointList& velocities,
                                double s, const Vec3& direction, double h) {
  const int d = knots.degree();
  const int k = knots.findSpan(s);
  BasisValues basis;
  evaluateBasis(knots, k, s, 1, basis);
  // Scale by the span's parameter length: b' * span is O(1) like b, whatever the parametrisation.
  const double scale = knots[k + 1] - knots[k];
  ConstraintRows row;
  row.first = k - d;
  row.count = d + 1;
  row.rowCount = 2;
  orthonormalComplement(direction, row.directions[0], row.directions[1]);
  row.directions[2] = Vec3::Zero();
  Vec3 derivative = Vec3::Zero();          // C'(s) * scale
  Vec3 derivativeVelocity = Vec3::Zero();  // Cdot'(s) * scale
  for (int a = 0; a <= d; ++a) {
    row.basis[a] = scale * basis.d[1][static_cast<size_t>(a)];
    derivative += row.basis[a] * points[static_cast<size_t>(row.first + a)];
    derivativeVelocity += row.basis[a] * velocities[static_cast<size_t>(row.first + a)];
  }
  for (int r = 0; r < 2; ++r) {
    row.rhs[r] = -row.directions[r].dot(derivative) / h - row.directions[r].dot(derivativeVelocity);
  }
  return row;
}

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
  owner_.clear();
  ownerRow_.clear();
  for (int p = 0; p < static_cast<int>(rows.size()); ++p) {
    for (int r = 0; r < rows[static_cast<size_t>(p)].rowCount; ++r) {
      owner_.push_back(p);
      ownerRow_.push_back(r);
    }
  }
  const int columns = static_cast<int>(owner_.size());
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
    lambdas_.resize(columns, 3);
  }
  for (int c = 0; c < columns; ++c) {
    const ConstraintRows& row = rows[static_cast<size_t>(owner_[static_cast<size_t>(c)])];
    const Vec3& direction = row.directions[ownerRow_[static_cast<size_t>(c)]];
    double* z = &z_[static_cast<size_t>(c) * static_cast<size_t>(size)];
    // The column starts at the first non-zero component of the direction at the first control point
    // (for a pin row along axis k: 3 first + k).
    int offset = 0;
    while (offset < 2 && direction[offset] == 0.0) ++offset;
    const int begin = 3 * row.first + offset;
    start_[static_cast<size_t>(c)] = begin;
    std::fill(z + begin, z + size, 0.0);
    for (int a = 0; a < row.count; ++a)
      for (int axis = offset; axis < 3; ++axis) z[3 * (row.first + a) + axis] = row.basis[a] * direction[axis];
  }
  substituteColumns(factor);
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
    const ConstraintRows& row = rows[static_cast<size_t>(owner_[static_cast<size_t>(r)])];
    lambda_(r) = projected - row.rhs[ownerRow_[static_cast<size_t>(r)]];
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

void ConstrainedSolver::substituteColumns(const SymmetricBandedMatrix& factor) {
  // Z = L^-1 G^T, up to three columns per pass over the factor: those that start within a half
  // bandwidth of each other (a pin's three rows, a clamp's two beside them), in the order of their
  // first rows. A pinned end's columns run the whole rope; one pass for three of them made a 256-point
  // rope pinned at both ends step 6 % faster (rod_benchmark, BM_RodStep/256: 223 -> 209 us, medians of
  // 3 interleaved runs). Each column gets the bits of its own substitution.
  const int size = factor.size();
  order_.clear();
  for (int c = 0; c < columns_; ++c) {  // insertion by first row, ties in column order (a handful of columns)
    size_t at = order_.size();
    order_.push_back(c);
    for (; at > 0 && start_[static_cast<size_t>(order_[at - 1])] > start_[static_cast<size_t>(c)]; --at) order_[at] = order_[at - 1];
    order_[at] = c;
  }
  for (int g = 0; g < columns_;) {
    double* columns[3];
    int firstRows[3];
    int count = 0;
    const int lead = start_[static_cast<size_t>(order_[static_cast<size_t>(g)])];
    while (count < 3 && g < columns_ &&
           start_[static_cast<size_t>(order_[static_cast<size_t>(g)])] - lead <= factor.halfBandwidth()) {
      const int c = order_[static_cast<size_t>(g++)];
      columns[count] = &z_[static_cast<size_t>(c) * static_cast<size_t>(size)];
      firstRows[count++] = start_[static_cast<size_t>(c)];
    }
    factor.forwardSubstituteColumns(columns, firstRows, count);
  }
}

void ConstrainedSolver::solveHomogeneous(const SymmetricBandedMatrix& factor, double* x, int firstRow) {
  factor.forwardSubstitute(x, firstRow);
  double* const columns[1] = {x};
  projectOutConstraints<1>(factor.size(), columns, firstRow, 0);
  factor.backSubstitute(x);
}

void ConstrainedSolver::solveHomogeneous3(const SymmetricBandedMatrix& factor, double* x, int firstRow, int lastRow) {
  const int size = factor.size();
  factor.forwardSubstitute3(x, firstRow);
  double* const columns[3] = {x, x + size, x + 2 * size};
  projectOutConstraints<3>(size, columns, firstRow, std::max(lastRow, 0));
  factor.backSubstitute3(x, lastRow);
}

template <int kCount>
void ConstrainedSolver::projectOutConstraints(int size, double* const* x, int firstRow, int lastRow) {
  // y <- y - Z lambda with lambda = (Z^T Z)^-1 Z^T y, the multipliers that keep G dv = 0, on kCount
  // right-hand sides at once: each constraint column is read once for all of them, and their sums
  // are independent chains (each in the one-column order, so the same bits). Rows before lastRow are
  // not corrected (solveHomogeneous3's back substitution stops at lastRow and never reads them).
  if (columns_ == 0) return;
  for (int r = 0; r < columns_; ++r) {
    const double* zr = &z_[static_cast<size_t>(r) * static_cast<size_t>(size)];
    double projected[kCount] = {};
    for (int i = std::max(start_[static_cast<size_t>(r)], firstRow); i < size; ++i)
      for (int k = 0; k < kCount; ++k) projected[k] += zr[i] * x[k][i];
    for (int k = 0; k < kCount; ++k) lambdas_(r, k) = projected[k];
  }
  for (int k = 0; k < kCount; ++k) {
    lambda_ = lambdas_.col(k);
    lambda_ = llt_.solve(lambda_);  // per right-hand side, whatever kCount
    lambdas_.col(k) = lambda_;
  }
  for (int r = 0; r < columns_; ++r) {
    const double* zr = &z_[static_cast<size_t>(r) * static_cast<size_t>(size)];
    double l[kCount];
    for (int k = 0; k < kCount; ++k) l[k] = lambdas_(r, k);
    for (int i = std::max(start_[static_cast<size_t>(r)], lastRow); i < size; ++i)
      for (int k = 0; k < kCount; ++k) x[k][i] -= zr[i] * l[k];
  }
}

}  // namespace rope
