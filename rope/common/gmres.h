// SPDX-License-Identifier: MIT
#pragma once
// GMRES for a small nonsymmetric system A x = b known only through products y = A x:
// Y. Saad and M. H. Schultz, "GMRES: A generalized minimal residual algorithm for solving
// nonsymmetric linear systems", SIAM J. Sci. Stat. Comput. 7(3):856-869, 1986 (Arnoldi with
// modified Gram-Schmidt, Givens rotations on the Hessenberg matrix, no restart).
//
// Why here: the sliding friction bounds of a rope wrapped round a support (bullet_bridge/contact/
// body_contacts.cpp) couple every sample with every other through the rod's step matrix; forming that
// m x m matrix costs m rod solves and an O(m^3) factorisation, while each GMRES product is one rod
// solve (Rod::trialGeneralizedResponse). Without restart the iterate minimises the residual over the
// whole Krylov space, so the result never gets worse with more iterations.
//
// Not API: installed only because bullet_bridge/contact/body_contacts.h holds a solver (its
// workspace); may change in any release.

#include <functional>

#include <Eigen/Core>

namespace rope {

struct GmresSettings {
  int maxIterations = 60;            // products of A at most, >= 1
  double relativeTolerance = 1e-10;  // stop when |b - A x| <= relativeTolerance |b|, > 0
};

struct GmresResult {
  int iterations = 0;               // products of A used
  double relativeResidual = 0.0;    // |b - A x| / |b| (0 for b = 0)
  bool converged = false;           // relativeResidual <= settings.relativeTolerance
};

class GmresSolver {
 public:
  // y = A x, both of `size` doubles (distinct arrays).
  using Product = std::function<void(const double* x, double* y)>;
  // Solves A x = b starting from x = 0; x receives the minimal-residual iterate even when it did not
  // converge. A non-finite product stops the iteration (converged = false, x the last finite
  // iterate). No allocation once the workspace has grown to size x (maxIterations + 1).
  GmresResult solve(int size, const Product& apply, const double* b, double* x, const GmresSettings& settings);

 private:
  Eigen::MatrixXd basis_;       // size x (k + 1): the orthonormal Arnoldi vectors
  Eigen::MatrixXd hessenberg_;  // (k + 1) x k, rotated to upper triangular as it grows
  Eigen::VectorXd cosines_, sines_, residual_, product_, coefficients_;
};

}  // namespace rope
