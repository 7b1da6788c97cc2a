#pragma once
// Point constraints on the curve ([A] §5.1 "6 constraints to fix the two extremities", spec §2
// "Constraints"): a pin holds C(s*) = sum_i b_i(s*) q_i at a target. It is linear in q, so with the
// implicit step q_new = q + h (v + dv) it becomes three rows on dv:
//   sum_i b_i(s*) dv_i = (target - C(s*)) / h - Cdot(s*),
// i.e. the end-of-step position is exactly the target (moving targets included): the position error
// is folded into the velocity-level constraint, so pins never drift.
// The rows are imposed with Lagrange multipliers through the Schur complement against the banded
// factor S = L L^T (never by deleting DOFs, so any s* works):
//   Z = L^-1 G^T,  (Z^T Z) lambda = Z^T L^-1 r - c,  dv = L^-T (L^-1 r - Z lambda).
// A row's column of G^T is zero before the pin's first control point, so its forward substitution
// starts there: a pin at the far end costs O(1), one at the near end O(n). The 3m x 3m Schur matrix is
// the only dense matrix (m pins, m small).

#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "rope/common/types.h"
#include "rope/rod/banded_matrix.h"
#include "rope/spline/knot_vector.h"

namespace rope {

struct Pin {
  int id = 0;
  double parameter = 0.0;  // s*
  Vec3 target = Vec3::Zero();  // m, where C(s*) is at the end of the next step
};

// One pin's three rows: basis values b_{first .. first+count-1}(s*) and the right-hand side c (m/s).
struct ConstraintRows {
  int first = 0;
  int count = 0;
  double basis[kMaxDegree + 1] = {};
  Vec3 rhs = Vec3::Zero();
};

// Whether pins at these parameters (sorted ascending, distinct) give independent rows: by the
// Schoenberg-Whitney theorem the rows b(s_1) .. b(s_m) of a spline's basis are independent exactly
// when basis functions i_1 < ... < i_m exist with b_{i_j}(s_j) != 0 (de Boor, "Total positivity of the
// spline collocation matrix", Indiana Univ. Math. J. 25 (1976) 541-551), found greedily in O(m d).
// False e.g. for more pins inside one knot span than it has basis functions (degree + 1).
bool pinRowsIndependent(const KnotVector& knots, const std::vector<double>& sortedParameters);

class ConstrainedSolver {
 public:
  // Only scratch space lives here: copies start empty (Eigen's LLT is not meant to be copied before
  // its first compute()).
  ConstrainedSolver() = default;
  ConstrainedSolver(const ConstrainedSolver&) {}
  ConstrainedSolver& operator=(const ConstrainedSolver&) {
    ready_ = false;
    return *this;
  }
  // factor: factorised 3n x 3n system; x: right-hand side r on entry, dv on return.
  // Returns false if the Schur complement is not positive definite (dependent pins) or not finite;
  // x is then unspecified (the caller keeps its own state).
  bool solve(const SymmetricBandedMatrix& factor, const std::vector<ConstraintRows>& rows, double* x);
  // After a successful solve() with the same factor: x <- the pinned response to the right-hand side x
  // with the pins' right-hand sides c = 0 (the linear part of solve(), reusing its Schur factor). Used
  // for extra impulses whose effect must respect the pins. Solving from the first non-zero row of x
  // (firstRow) skips work for loads near the far end.
  void solveHomogeneous(const SymmetricBandedMatrix& factor, double* x, int firstRow = 0);
  // Whether solveHomogeneous may be called (a solve() succeeded and this is not a copy made since).
  bool ready() const { return ready_; }

 private:
  int columns_ = 0;
  bool ready_ = false;
  std::vector<double> z_;        // 3m columns of length N
  std::vector<int> start_;       // first non-zero row of each column
  Eigen::MatrixXd schur_;
  Eigen::VectorXd lambda_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
};

}  // namespace rope
