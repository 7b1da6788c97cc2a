// SPDX-License-Identifier: MIT
#pragma once
// Point constraints on the curve (docs/method.md §9, eqs. 25–26; [A] §5.1 "6 constraints to fix the
// two extremities"): a pin holds C(s*) = sum_i b_i(s*) q_i at a target. It is linear in q, so with the
// implicit step q_new = q + h (v + dv) it becomes three rows on dv:
//   sum_i b_i(s*) dv_i = (target - C(s*)) / h - Cdot(s*),
// i.e. the end-of-step position is exactly the target (moving targets included): the position error
// is folded into the velocity-level constraint, so pins never drift.
//
// A clamp (a weld; docs/method.md §9) is a pin that also holds the curve's tangent at s*
// along a unit direction d. The tangent condition is imposed as P C'(s*) = 0 with P = I - d d^T,
// i.e. two rows e_k . C'(s*) = 0 for an orthonormal pair e_1, e_2 orthogonal to d. Like the pin it is
// linear in q, so on the end-of-step positions it reads
//   sum_i b_i'(s*) e_k . dv_i = -(e_k . C'(s*)) / h - e_k . Cdot'(s*),
// and holds exactly at the end of every step: nothing is linearised, nothing drifts, and a direction
// that moves (a turning nozzle) is reached at the end of the step like a moving pin's target. The
// alternative C'/|C'| = d is nonlinear (its linearisation would drift) and would also fix the
// stretch |C'| at s*, which belongs to the material law; P C' = 0 leaves the component along d free.
// It does not exclude C' antiparallel to d, which needs the rope to fold back on itself at s* within
// one step; Rod checks the sign after the solve and reports such a step as failed. Rows are scaled by
// the knot span's parameter length so that b' is O(1) like b (the scale changes nothing but the
// conditioning of the Schur complement).
//
// The rows are imposed with Lagrange multipliers through the Schur complement against the banded
// factor S = L L^T (never by deleting DOFs, so any s* works):
//   Z = L^-1 G^T,  (Z^T Z) lambda = Z^T L^-1 r - c,  dv = L^-T (L^-1 r - Z lambda).
// A row's column of G^T is zero before the constraint's first control point, so its forward
// substitution starts there: a pin at the far end costs O(1), one at the near end O(n). The
// Schur matrix (3 rows per pin, 5 per clamp) is the only dense matrix (few constraints).
// Not API (except Pin, which Rod::pins() returns): installed only because rope/rod/rod.h holds a solver.

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
  // Clamps only: the unit vector the tangent C'(s*)/|C'(s*)| points along at the end of the next
  // step. Zero for a plain pin.
  Vec3 direction = Vec3::Zero();
  bool isClamp() const { return direction.squaredNorm() > 0.0; }
};

// Up to three rows on dv that share one set of basis values: row r reads
//   sum_a basis[a] * (directions[r] . dv_{first+a}) = rhs[r].
// A pin is three rows along the axes with the basis values b(s*); a clamp's tangent condition is two
// rows along e_1, e_2 with the scaled derivatives b'(s*).
struct ConstraintRows {
  int first = 0;
  int count = 0;
  double basis[kMaxDegree + 1] = {};
  Vec3 rhs = Vec3::Zero();
  int rowCount = 3;  // 1..3
  Vec3 directions[3] = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
};

// A pin's three rows at the state (points, velocities) for a step of h seconds (see above).
ConstraintRows pinRows(const KnotVector& knots, const PointList& points, const PointList& velocities, double s,
                       const Vec3& target, double h);

// A clamp's two tangent rows for the unit direction. The caller guarantees s in the valid range,
// |direction| = 1 and h > 0 (the rod's own state).
ConstraintRows clampTangentRows(const KnotVector& knots, const PointList& points, const PointList& velocities,
                                double s, const Vec3& direction, double h);

// Unit vectors e_1, e_2 with (e_1, e_2, direction) orthonormal and right-handed, chosen
// deterministically from the direction alone.
void orthonormalComplement(const Vec3& direction, Vec3& e1, Vec3& e2);

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
  // The same for three right-hand sides x[0..N), x[N..2N), x[2N..3N) at once (N = factor.size()),
  // each with exactly the arithmetic of solveHomogeneous. With lastRow > 0 only the rows from lastRow
  // on are computed (the rows before it unspecified): what a response read at rows at or after its
  // own load needs, for less back substitution.
  void solveHomogeneous3(const SymmetricBandedMatrix& factor, double* x, int firstRow = 0, int lastRow = 0);
  // Whether solveHomogeneous may be called (a solve() succeeded and this is not a copy made since).
  bool ready() const { return ready_; }

 private:
  // Between the substitutions of solveHomogeneous (kCount = 1) and solveHomogeneous3 (3): each y <- y - Z lambda
  // with the multipliers lambda = (Z^T Z)^-1 Z^T y that keep G dv = 0, on the rows from lastRow on
  // (nothing without constraints).
  template <int kCount>
  void projectOutConstraints(int size, double* const* x, int firstRow, int lastRow);
  // z_ <- L^-1 z_ on every constraint column, from its first row (start_).
  void substituteColumns(const SymmetricBandedMatrix& factor);
  int columns_ = 0;
  bool ready_ = false;
  std::vector<int> owner_;       // constraint (index into rows) of each column
  std::vector<int> ownerRow_;    // its row (0..rowCount-1)
  std::vector<double> z_;        // one column of length N per row
  std::vector<int> start_;       // first non-zero row of each column
  Eigen::MatrixXd schur_;
  Eigen::VectorXd lambda_;
  Eigen::MatrixXd lambdas_;      // projectOutConstraints' multipliers, one column per right-hand side
  std::vector<int> order_;       // the columns by first row (substituteColumns)
  Eigen::LLT<Eigen::MatrixXd> llt_;
};

}  // namespace rope
