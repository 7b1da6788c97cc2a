// SPDX-License-Identifier: MIT
#pragma once
// Symmetric block-banded matrix with its in-place banded Cholesky factorisation (docs/method.md §8:
// eq. 22 is solved in O(n)). Blocks are b x b (b = 1 for the scalar mass matrix, b = 3 for
// the rod's system); blocks (i, j) with |i - j| <= d may be non-zero, so in scalars the half bandwidth
// is w = b (d + 1) - 1. Only the lower band is stored: N (w + 1) doubles, no dense N x N anywhere.
// Factorising costs O(N w^2), a solve O(N w). Failure (a non-positive or non-finite pivot) is
// reported, never turned into NaN.
// Not API: installed only because rope/rod/rod.h holds one; it may change in any release.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace rope {

class SymmetricBandedMatrix {
 public:
  void prefetch() const;  // cache hints for the band (rope/common/prefetch.h)
  SymmetricBandedMatrix() = default;
  // Zero matrix of blockCount x blockCount blocks of size blockSize with block half bandwidth
  // blockBandwidth. Reuses the storage's capacity when it is big enough (no allocation in a steady
  // state); holds only the new band.
  void reset(int blockCount, int blockSize, int blockBandwidth);
  void setZero();

  int size() const { return size_; }                 // N = blockCount * blockSize
  int halfBandwidth() const { return bandwidth_; }   // w
  int blockSize() const { return blockSize_; }
  bool factorized() const { return factorized_; }
  // Doubles held, N (w + 1): what a copy of the matrix copies (the band in use, never more).
  std::size_t storedEntries() const { return band_.size(); }

  // Scalar entry (row >= col, row - col <= w); only before factorize().
  double& at(int row, int col) { return band_[index(row, col)]; }
  double at(int row, int col) const { return band_[index(row, col)]; }
  // Symmetric read of any entry (zero outside the band), for tests and diagnostics.
  double entry(int row, int col) const;
  // Adds a 3x3 block at block (i, j), i >= j (blockSize 3). For i == j only the lower triangle is read.
  // Inline: the rod adds every contact sample's spring as ten scaled blocks per trial pass, and a call
  // made each scaled block go through memory first. Out of line it was 4.3 % of the 2 m pile's
  // instructions; inline the pile's substep takes 2.6 % fewer (callgrind, 0-2 s).
  void addBlock(int i, int j, const Eigen::Matrix3d& block) {
    const int r0 = 3 * i;
    const int c0 = 3 * j;
    for (int a = 0; a < 3; ++a) {
      const int bEnd = (i == j) ? a + 1 : 3;
      for (int b = 0; b < bEnd; ++b) at(r0 + a, c0 + b) += block(a, b);
    }
  }
  // Adds value * I to block (i, j), i >= j.
  void addScaledIdentity(int i, int j, double value);

  // y = A x (x, y of length N, distinct); only before factorize().
  void multiply(const double* x, double* y) const;

  // In-place Cholesky A = L L^T. Returns false (and leaves the matrix unusable until reset) if a
  // pivot is not finite or not positive: the matrix is not positive definite.
  bool factorize();
  // With the factor: x <- L^-1 x, starting at firstRow (entries above it must be zero: a sparse
  // right-hand side skips the leading rows, which makes constraint columns at the far end O(1)).
  void forwardSubstitute(double* x, int firstRow = 0) const;
  // x <- L^-T x.
  void backSubstitute(double* x) const;
  // The same for three right-hand sides at once, x[0..N), x[N..2N), x[2N..3N) (the responses to
  // impulses along x, y, z): one pass over the factor instead of three, and three independent
  // chains of divisions in flight. Each column's arithmetic is exactly that of the one-column form.
  void forwardSubstitute3(double* x, int firstRow = 0) const;
  // The same on `count` columns anywhere, each of N, each from its own first row (constraint columns
  // that start a few rows apart), three at a time in the order given: each column's arithmetic is
  // exactly that of forwardSubstitute(columns[k], firstRows[k]). count <= 0: nothing.
  void forwardSubstituteColumns(double* const* columns, const int* firstRows, int count) const;
  // x <- L^-T x on the rows from lastRow on; the rows before it are left partly updated (unspecified).
  // Those rows feed none of the later ones, so a caller that reads only rows >= lastRow (a response
  // read at curve points after the impulse's own) skips their share of the work, bitwise as the full pass.
  void backSubstitute3(double* x, int lastRow = 0) const;
  // x <- A^-1 x.
  void solve(double* x) const;

 private:
  int index(int row, int col) const { return row * (bandwidth_ + 1) + (col - row + bandwidth_); }
  // forwardSubstituteColumns on at most three columns.
  void forwardSubstituteChunk(double* const* columns, const int* firstRows, int count) const;
  // Rows [firstRow, endRow) of forwardSubstitute(x, firstRow).
  void forwardSubstituteRows(double* x, int firstRow, int endRow) const;
  // Rows [joint, N) of forwardSubstitute on kCount columns whose first rows all lie at or before
  // joint - w (so every sum runs over the whole band), the rows before joint done.
  template <int kCount>
  void forwardSubstituteJoint(double* const* columns, int joint) const;
  int size_ = 0;
  int blockSize_ = 1;
  int bandwidth_ = 0;
  bool factorized_ = false;
  std::vector<double> band_;  // row-major, w + 1 entries per row: columns row - w .. row
  std::vector<double> inverseDiagonal_;  // 1 / L(c, c), once factorized: the substitutions multiply by it
  std::vector<double> column_;  // factorize()'s scratch: the current column of L below the diagonal
};

}  // namespace rope
