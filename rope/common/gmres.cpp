// SPDX-License-Identifier: MIT
#include "rope/common/gmres.h"

#include <algorithm>
#include <cmath>

namespace rope {

GmresResult GmresSolver::solve(int size, const Product& apply, const double* b, double* x,
                               const GmresSettings& settings) {
  GmresResult result;
  Eigen::Map<Eigen::VectorXd> solution(x, size);
  solution.setZero();
  const Eigen::Map<const Eigen::VectorXd> rhs(b, size);
  const double rhsNorm = rhs.norm();
  if (size == 0 || rhsNorm == 0.0) {
    result.converged = true;
    return result;
  }
  if (!std::isfinite(rhsNorm)) return result;
  const int k = std::max(1, std::min(settings.maxIterations, size));
  // The workspace only grows (Eigen's resize reallocates on any change of size, and the number of
  // sliding samples changes from pass to pass); the solve uses its leading part.
  if (basis_.rows() < size || basis_.cols() < k + 1) {
    basis_.resize(std::max<Eigen::Index>(basis_.rows(), size), std::max<Eigen::Index>(basis_.cols(), k + 1));
  }
  if (hessenberg_.rows() < k + 1) hessenberg_.resize(k + 1, k);
  if (cosines_.size() < k) {
    cosines_.resize(k);
    sines_.resize(k);
    coefficients_.resize(k);
  }
  if (residual_.size() < k + 1) residual_.resize(k + 1);
  if (product_.size() < size) product_.resize(size);
  residual_.head(k + 1).setZero();
  auto product = product_.head(size);
  basis_.col(0).head(size) = rhs / rhsNorm;
  residual_(0) = rhsNorm;  // the least-squares right-hand side |b| e_1, rotated as H is
  int used = 0;
  double residualNorm = rhsNorm;
  for (int j = 0; j < k; ++j) {
    apply(basis_.col(j).data(), product.data());
    ++result.iterations;
    if (!product.allFinite()) break;
    // Arnoldi with modified Gram-Schmidt: H(0..j+1, j).
    for (int i = 0; i <= j; ++i) {
      const double h = basis_.col(i).head(size).dot(product);
      hessenberg_(i, j) = h;
      product -= h * basis_.col(i).head(size);
    }
    const double next = product.norm();
    hessenberg_(j + 1, j) = next;
    // The earlier rotations, then a new one that zeroes H(j+1, j).
    for (int i = 0; i < j; ++i) {
      const double a = hessenberg_(i, j), c = hessenberg_(i + 1, j);
      hessenberg_(i, j) = cosines_(i) * a + sines_(i) * c;
      hessenberg_(i + 1, j) = -sines_(i) * a + cosines_(i) * c;
    }
    const double diagonal = std::hypot(hessenberg_(j, j), next);
    if (!(diagonal > 0.0)) break;  // A maps the new direction to 0 within the space: singular
    cosines_(j) = hessenberg_(j, j) / diagonal;
    sines_(j) = next / diagonal;
    hessenberg_(j, j) = diagonal;
    hessenberg_(j + 1, j) = 0.0;
    residual_(j + 1) = -sines_(j) * residual_(j);
    residual_(j) *= cosines_(j);
    used = j + 1;
    residualNorm = std::abs(residual_(j + 1));
    if (residualNorm <= settings.relativeTolerance * rhsNorm || !(next > 0.0)) break;  // converged, or exact
    basis_.col(j + 1).head(size) = product / next;
  }
  if (used == 0) return result;
  // x = V y, H y = the rotated residual (back substitution on the triangle).
  auto coefficients = coefficients_.head(used);
  coefficients = residual_.head(used);
  hessenberg_.topLeftCorner(used, used).triangularView<Eigen::Upper>().solveInPlace(coefficients);
  solution.noalias() = basis_.topLeftCorner(size, used) * coefficients;
  result.relativeResidual = residualNorm / rhsNorm;
  result.converged = result.relativeResidual <= settings.relativeTolerance;
  return result;
}

}  // namespace rope
