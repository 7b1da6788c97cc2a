// SPDX-License-Identifier: MIT
#include "rope/rod/banded_matrix.h"

#include <algorithm>
#include <cmath>
#include "rope/common/prefetch.h"

namespace rope {

void SymmetricBandedMatrix::reset(int blockCount, int blockSize, int blockBandwidth) {
  blockSize_ = blockSize;
  size_ = blockCount * blockSize;
  bandwidth_ = blockSize * (blockBandwidth + 1) - 1;
  const size_t needed = static_cast<size_t>(size_) * static_cast<size_t>(bandwidth_ + 1);
  // Exactly the band in use (the capacity stays, so a rod that refines again does not allocate): a
  // copy of the matrix copies size() entries, and a rope coarsened from 16 to 4 control points kept
  // copying its 16-point band (4.6 KB; Rod's assembly cache, every substep) while using a quarter.
  band_.resize(needed);
  if (column_.size() < static_cast<size_t>(bandwidth_)) column_.resize(static_cast<size_t>(bandwidth_));
  setZero();
}

void SymmetricBandedMatrix::setZero() {
  const size_t used = static_cast<size_t>(size_) * static_cast<size_t>(bandwidth_ + 1);
  std::fill(band_.begin(), band_.begin() + static_cast<std::ptrdiff_t>(used), 0.0);
  factorized_ = false;
}

double SymmetricBandedMatrix::entry(int row, int col) const {
  if (row < col) std::swap(row, col);
  if (row - col > bandwidth_) return 0.0;
  return at(row, col);
}

void SymmetricBandedMatrix::addScaledIdentity(int i, int j, double value) {
  const int r0 = blockSize_ * i;
  const int c0 = blockSize_ * j;
  for (int a = 0; a < blockSize_; ++a) at(r0 + a, c0 + a) += value;
}

void SymmetricBandedMatrix::multiply(const double* x, double* y) const {
  for (int r = 0; r < size_; ++r) y[r] = 0.0;
  for (int r = 0; r < size_; ++r) {
    const int c0 = std::max(0, r - bandwidth_);
    const double* row = &band_[static_cast<size_t>(index(r, c0))];
    double sum = row[r - c0] * x[r];
    for (int c = c0; c < r; ++c) {
      sum += row[c - c0] * x[c];
      y[c] += row[c - c0] * x[r];
    }
    y[r] += sum;
  }
}

bool SymmetricBandedMatrix::factorize() {
  // Right-looking: column c of L, then its rank-one update of the trailing band,
  // A(i, j) -= L(i, c) L(j, c) for c < j <= i <= c + w. Each entry receives its terms in the order of
  // the textbook left-looking sums (k = c increasing), so the factor is bitwise that of
  // L(r, c) = (A(r, c) - sum_k L(r, k) L(c, k)) * (1 / L(c, c)). Why not left-looking: there every
  // entry is one chain of dependent subtractions (~4 cycles each); here the updates of a column are
  // independent of each other and contiguous along each row, so they pipeline (3.5x faster on the
  // rod's w = 11: rod_benchmark, BM_BandedFactorize). Why the reciprocal: one division per column
  // instead of w, and the substitutions multiply by it too, where a division (~14 cycles against 4)
  // lay on the chain from each solved row to the next; the 2 m pile's step was 7 % shorter and the
  // knot's 4 % (contact_benchmark, alternating runs), at up to one rounding more per entry.
  const int w = bandwidth_;
  double* column = column_.data();  // column[i - c - 1] = L(i, c)
  inverseDiagonal_.resize(static_cast<size_t>(size_));
  for (int c = 0; c < size_; ++c) {
    double& diagonal = band_[static_cast<size_t>(index(c, c))];
    const double pivot = diagonal;
    // isfinite first: an ordered comparison with NaN would raise FE_INVALID.
    if (!std::isfinite(pivot) || pivot <= 0.0) return false;
    diagonal = std::sqrt(pivot);
    const double inverse = 1.0 / diagonal;
    inverseDiagonal_[static_cast<size_t>(c)] = inverse;
    const int count = std::min(size_ - 1, c + w) - c;  // rows below c inside the band
    for (int a = 0; a < count; ++a) {
      double& entry = band_[static_cast<size_t>(index(c + 1 + a, c))];
      entry *= inverse;
      column[a] = entry;
    }
    for (int a = 0; a < count; ++a) {
      const double lower = column[a];
      double* row = &band_[static_cast<size_t>(index(c + 1 + a, c + 1))];  // row[b] = A(c + 1 + a, c + 1 + b)
      for (int b = 0; b <= a; ++b) row[b] -= lower * column[b];
    }
  }
  factorized_ = true;
  return true;
}

void SymmetricBandedMatrix::forwardSubstitute(double* x, int firstRow) const {
  forwardSubstituteRows(x, firstRow, size_);
}

void SymmetricBandedMatrix::forwardSubstituteRows(double* x, int firstRow, int endRow) const {
  const int w = bandwidth_;
  for (int r = firstRow; r < endRow; ++r) {
    const int c0 = std::max(firstRow, r - w);
    const double* row = &band_[static_cast<size_t>(r) * static_cast<size_t>(w + 1)];  // row[c - r + w] = L(r, c)
    double sum = x[r];
    for (int c = c0; c < r; ++c) sum -= row[c - r + w] * x[c];
    x[r] = sum * inverseDiagonal_[static_cast<size_t>(r)];
  }
}

void SymmetricBandedMatrix::backSubstitute(double* x) const {
  // x_c = (y_c - sum_k L(k, c) x_k) / L(c, c), k from the largest down (see backSubstitute3).
  const int w = bandwidth_;
  const size_t stride = static_cast<size_t>(w);  // from L(k, c) to L(k - 1, c) in the band
  for (int c = size_ - 1; c >= 0; --c) {
    const int kLast = std::min(size_ - 1, c + w);
    double sum = x[c];
    const double* l = &band_[static_cast<size_t>(index(kLast, c))];
    for (int k = kLast; k > c; --k, l -= stride) sum -= *l * x[k];
    x[c] = sum * inverseDiagonal_[static_cast<size_t>(c)];
  }
}

void SymmetricBandedMatrix::forwardSubstitute3(double* x, int firstRow) const {
  double* const columns[3] = {x, x + size_, x + 2 * size_};
  const int firstRows[3] = {firstRow, firstRow, firstRow};
  forwardSubstituteColumns(columns, firstRows, 3);
}

void SymmetricBandedMatrix::forwardSubstituteColumns(double* const* columns, const int* firstRows, int count) const {
  for (int k = 0; k < count; k += 3) forwardSubstituteChunk(columns + k, firstRows + k, std::min(3, count - k));
}

void SymmetricBandedMatrix::forwardSubstituteChunk(double* const* columns, const int* firstRows, int count) const {
  // Each column alone up to the row from which every column's sums run over the whole band (w rows
  // past the last first row), then all of them together: one pass over the factor for the rest, and
  // independent chains of subtractions in flight. A row's terms still come in increasing c, so every
  // column gets the bits of its one-column substitution.
  int joint = 0;
  for (int k = 0; k < count; ++k) joint = std::max(joint, firstRows[k]);
  joint = std::min(size_, joint + bandwidth_);
  for (int k = 0; k < count; ++k) forwardSubstituteRows(columns[k], firstRows[k], joint);
  if (count == 3) {
    forwardSubstituteJoint<3>(columns, joint);
  } else if (count == 2) {
    forwardSubstituteJoint<2>(columns, joint);
  } else if (count == 1) {
    forwardSubstituteJoint<1>(columns, joint);
  }
}

template <int kCount>
void SymmetricBandedMatrix::forwardSubstituteJoint(double* const* columns, int joint) const {
  const int w = bandwidth_;
  for (int r = joint; r < size_; ++r) {
    const double* row = &band_[static_cast<size_t>(r) * static_cast<size_t>(w + 1)];  // row[c - r + w] = L(r, c)
    double sum[kCount];
    for (int k = 0; k < kCount; ++k) sum[k] = columns[k][r];
    for (int c = r - w; c < r; ++c) {
      const double l = row[c - r + w];
      for (int k = 0; k < kCount; ++k) sum[k] -= l * columns[k][c];
    }
    const double inverse = inverseDiagonal_[static_cast<size_t>(r)];
    for (int k = 0; k < kCount; ++k) columns[k][r] = sum[k] * inverse;
  }
}

void SymmetricBandedMatrix::backSubstitute3(double* x, int lastRow) const {
  // Row by row, x_c = (y_c - sum_k L(k, c) x_k) / L(c, c) with the sums in registers, k taken from
  // the largest down: the same operations in the same order as subtracting each solved x_k from the
  // rows above it as soon as it is known (backSubstitute), so the same bits, without a store per term.
  const int w = bandwidth_;
  const size_t stride = static_cast<size_t>(w);  // from L(k, c) to L(k - 1, c) in the band
  double* x0 = x;
  double* x1 = x + size_;
  double* x2 = x + 2 * size_;
  lastRow = std::max(lastRow, 0);
  for (int c = size_ - 1; c >= lastRow; --c) {
    const int kLast = std::min(size_ - 1, c + w);
    double sum0 = x0[c], sum1 = x1[c], sum2 = x2[c];
    const double* l = &band_[static_cast<size_t>(index(kLast, c))];
    for (int k = kLast; k > c; --k, l -= stride) {
      sum0 -= *l * x0[k];
      sum1 -= *l * x1[k];
      sum2 -= *l * x2[k];
    }
    const double inverse = inverseDiagonal_[static_cast<size_t>(c)];
    x0[c] = sum0 * inverse;
    x1[c] = sum1 * inverse;
    x2[c] = sum2 * inverse;
  }
}

void SymmetricBandedMatrix::solve(double* x) const {
  forwardSubstitute(x, 0);
  backSubstitute(x);
}

void SymmetricBandedMatrix::prefetch() const { prefetchVector(band_); }

}  // namespace rope
