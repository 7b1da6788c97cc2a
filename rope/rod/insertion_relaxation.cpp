// SPDX-License-Identifier: MIT
#include "rope/rod/insertion_relaxation.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "rope/rod/bending_energy.h"
#include "rope/rod/stretching_energy.h"
#include "rope/spline/bspline_basis.h"

namespace rope {

namespace {

// The internal energy (J) of spans [firstSpan, lastSpan] and, if gradient is not null, its gradient
// with respect to their points; window[i] is control point firstSpan + i (and so is gradient[i]).
// hessian (if not null): the Gauss–Newton (clamped, positive semidefinite) stiffness of the same
// points, 3 x 3 blocks, dense.
double localInternalEnergy(const RodIntegrals& integrals, double axialStiffness, const PointList& window,
                           int firstSpan, int lastSpan, std::vector<Vec3>* gradient,
                           Eigen::MatrixXd* hessian = nullptr) {
  const int local = integrals.degree() + 1;
  const int points = lastSpan - firstSpan + local;
  if (gradient != nullptr) gradient->assign(static_cast<size_t>(points), Vec3::Zero());
  if (hessian != nullptr) hessian->setZero(3 * points, 3 * points);
  Vec3 forces[kMaxDegree + 1];
  Vec3* const spanForces = gradient != nullptr ? forces : nullptr;  // the energy alone: no forces
  Eigen::Matrix3d blocks[(kMaxDegree + 1) * (kMaxDegree + 1)];
  double energy = 0.0;
  for (int j = firstSpan; j <= lastSpan; ++j) {
    const SpanView span = integrals.span(j);
    const int at = j - firstSpan;
    const Vec3* q = &window[static_cast<size_t>(at)];
    for (int a = 0; a < local; ++a) forces[a].setZero();
    energy += stretchingSpan(span, q, axialStiffness, StiffnessMode::kClamped, spanForces,
                             hessian != nullptr ? blocks : nullptr);
    energy = bendingSpan(span, q, spanForces, energy);
    if (hessian != nullptr) {
      for (int a = 0; a < local; ++a)
        for (int b = 0; b <= a; ++b) {
          Eigen::Matrix3d block = blocks[a * local + b];
          block.diagonal().array() += span.bending[a * local + b];
          hessian->block<3, 3>(3 * (at + a), 3 * (at + b)) += block;
          if (b != a) hessian->block<3, 3>(3 * (at + b), 3 * (at + a)) += block.transpose();
        }
    }
    if (gradient != nullptr) {
      for (int a = 0; a < local; ++a) (*gradient)[static_cast<size_t>(at + a)] -= forces[a];
    }
  }
  return energy;
}

Eigen::VectorXd lumpedMetric(const Eigen::VectorXd& lumped) {
  Eigen::VectorXd metric(3 * lumped.size());
  for (Eigen::Index i = 0; i < lumped.size(); ++i) metric.segment<3>(3 * i).setConstant(lumped[i]);
  return metric;
}

// One attempt on points[first..last] (see relaxInsertion).
InsertionRelaxation relaxWindow(const KnotVector& knots, const RodIntegrals& integrals, double axialStiffness,
                                double excess, int first, int last, const std::vector<ConstraintRows>& rows,
                                const std::vector<std::pair<double, double>>& pointMasses, PointList& points) {
  InsertionRelaxation result;
  result.excess = excess;
  if (!(excess > 0.0)) return result;
  result.remaining = excess;
  const int d = integrals.degree();
  const int n = static_cast<int>(points.size());
  first = std::max(first, 0);
  last = std::min(last, n - 1);
  if (last < first) return result;
  const int firstSpan = std::max(0, first - d);
  const int lastSpan = std::min(integrals.spanCount() - 1, last);
  const int count = last - first + 1;
  const int unknowns = 3 * count;

  // Lumped masses g_a = mu int b_a l0' ds (+ point masses): the metric and the centre-of-mass rows.
  Eigen::VectorXd lumped = Eigen::VectorXd::Zero(count);
  for (int j = firstSpan; j <= lastSpan; ++j) {
    const SpanView span = integrals.span(j);
    for (int a = 0; a < span.localCount; ++a) {
      const int i = j + a - first;
      if (i >= 0 && i < count) lumped[i] += span.gravity[a];
    }
  }
  BasisValues basis;
  for (const auto& [s, mass] : pointMasses) {
    const int k = knots.findSpanUnchecked(s);
    evaluateBasis(knots, k, s, 0, basis);
    for (int a = 0; a <= d; ++a) {
      const int i = basis.firstIndex() + a - first;
      if (i >= 0 && i < count) lumped[i] += mass * basis.d[0][static_cast<size_t>(a)];
    }
  }
  if (!(lumped.minCoeff() > 0.0)) return result;

  // Conditions on the displacement: centre of mass (3 rows), then every pin or clamp row that reaches
  // a moved point.
  std::vector<Eigen::VectorXd> conditions;
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd row = Eigen::VectorXd::Zero(unknowns);
    for (int i = 0; i < count; ++i) row[3 * i + c] = lumped[i];
    conditions.push_back(row);
  }
  for (const ConstraintRows& constraint : rows) {
    for (int r = 0; r < constraint.rowCount; ++r) {
      Eigen::VectorXd row = Eigen::VectorXd::Zero(unknowns);
      for (int a = 0; a < constraint.count; ++a) {
        const int i = constraint.first + a - first;
        if (i < 0 || i >= count) continue;
        for (int c = 0; c < 3; ++c) row[3 * i + c] = constraint.basis[a] * constraint.directions[r][c];
      }
      if (row.squaredNorm() > 0.0) conditions.push_back(row);
    }
  }
  Eigen::MatrixXd A(static_cast<Eigen::Index>(conditions.size()), unknowns);
  for (size_t r = 0; r < conditions.size(); ++r) A.row(static_cast<Eigen::Index>(r)) = conditions[r].transpose();
  // Z: an orthonormal basis of the displacements with A dq = 0 (the last columns of A^T's full QR
  // beyond its rank; the rank tolerates dependent rows, e.g. a pin that the centre-of-mass rows imply).
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A.transpose());
  const Eigen::Index rank = qr.rank();
  if (rank >= unknowns) return result;  // no freedom left
  const Eigen::MatrixXd Q = qr.householderQ();
  const Eigen::MatrixXd Z = Q.rightCols(unknowns - rank);

  // The points the spans read, copied once: trials change only the moved ones.
  PointList window(points.begin() + firstSpan, points.begin() + lastSpan + d + 1);
  const int offset = first - firstSpan;  // window index of points[first]
  std::vector<Vec3> gradient;
  Eigen::MatrixXd hessian;
  double energy = localInternalEnergy(integrals, axialStiffness, window, firstSpan, lastSpan, &gradient, &hessian);
  const double target = energy - excess;
  PointList trial = window;
  // The least displacement reaching the target, found on the Levenberg–Marquardt path of the energy's
  // quadratic model, dq(lambda) = -lambda (W + lambda H)^-1 g restricted to A dq = 0 (lambda in s^2: it
  // is the displacement of an implicit relaxation step of squared length lambda): small lambda moves
  // along the mass-weighted gradient, large lambda reaches the Newton step. lambda is searched on a
  // log scale against the true energy; if even the Newton end stays above the target, the lowest point
  // found is taken and the path is rebuilt there.
  const Eigen::MatrixXd reducedMetric = Z.transpose() * lumpedMetric(lumped).asDiagonal() * Z;
  Eigen::VectorXd modal, reduced, dq;  // energyAt's, kept across its calls
  constexpr int kMaxRebuilds = 8;
  for (; result.iterations < kMaxRebuilds && energy > target; ++result.iterations) {
    Eigen::VectorXd g(unknowns);
    for (int i = 0; i < count; ++i) g.segment<3>(3 * i) = gradient[static_cast<size_t>(offset + i)];
    const Eigen::MatrixXd H = hessian.block(3 * offset, 3 * offset, unknowns, unknowns);
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(Z.transpose() * H * Z, reducedMetric);
    if (modes.info() != Eigen::Success) break;
    const Eigen::VectorXd frequencies = modes.eigenvalues().cwiseMax(0.0);  // 1/s^2
    const Eigen::VectorXd load = modes.eigenvectors().transpose() * (Z.transpose() * g);
    const double stiffest = frequencies.maxCoeff();
    if (!(stiffest > 0.0) || !load.allFinite()) break;
    auto energyAt = [&](double lambda) {
      modal = (lambda * load.array() / (1.0 + lambda * frequencies.array())).matrix();
      reduced.noalias() = modes.eigenvectors() * modal;
      dq.noalias() = Z * reduced;
      for (int i = 0; i < count; ++i)
        trial[static_cast<size_t>(offset + i)] = window[static_cast<size_t>(offset + i)] - dq.segment<3>(3 * i);
      return localInternalEnergy(integrals, axialStiffness, trial, firstSpan, lastSpan, nullptr);
    };
    // Bracket: lambda from 1e-8 / (stiffest mode) (a move of 1e-8 of the Newton step along it) upwards by
    // 10x, up to 1e6 / (stiffest mode) (every mode down to 1e-6 of the stiffest's frequency squared at
    // least half-way to its Newton step).
    double low = 0.0, high = 1e-8 / stiffest, best = 0.0, bestEnergy = energy;
    double highEnergy = energyAt(high);
    while (highEnergy > target && high < 1e6 / stiffest) {
      if (highEnergy < bestEnergy) best = high, bestEnergy = highEnergy;
      low = high;
      high *= 10.0;
      highEnergy = energyAt(high);
    }
    if (highEnergy < bestEnergy) best = high, bestEnergy = highEnergy;
    if (highEnergy <= target) {
      // Bisection on log lambda to within 1e-3 of the excess below the target.
      for (int k = 0; k < 60 && highEnergy < target - 1e-3 * excess && low > 0.0 && high > 1.0001 * low; ++k) {
        const double mid = std::sqrt(low * high);
        const double midEnergy = energyAt(mid);
        if (midEnergy <= target) high = mid, highEnergy = midEnergy;
        else low = mid;
      }
      best = high;
    }
    if (!(best > 0.0)) break;
    energyAt(best);
    window = trial;
    energy = localInternalEnergy(integrals, axialStiffness, window, firstSpan, lastSpan, &gradient, &hessian);
  }
  result.remaining = std::max(0.0, energy - target);
  for (int i = 0; i < count; ++i) {
    Vec3& point = points[static_cast<size_t>(first + i)];
    result.displacement = std::max(result.displacement, (window[static_cast<size_t>(offset + i)] - point).norm());
    point = window[static_cast<size_t>(offset + i)];
  }
  return result;
}

}  // namespace

InsertionRelaxation relaxInsertion(const KnotVector& knots, const RodIntegrals& integrals, double axialStiffness,
                                   double excess, int first, int last, const std::vector<ConstraintRows>& rows,
                                   const std::vector<std::pair<double, double>>& pointMasses, PointList& points) {
  // Where pins, a clamp or the rope's end leave the new knot's points too little freedom, the window
  // widens by one point on each side, up to kMaxWidening times, continuing from where the last
  // attempt left the points.
  constexpr int kMaxWidening = 3;
  InsertionRelaxation total;
  total.excess = total.remaining = excess;
  if (!(excess > 0.0)) {
    total.remaining = 0.0;
    return total;
  }
  // Only points[first - kMaxWidening .. last + kMaxWidening] can move.
  const int from = std::max(0, first - kMaxWidening);
  const int to = std::min(static_cast<int>(points.size()) - 1, last + kMaxWidening);
  if (to < from) return total;
  const PointList start(points.begin() + from, points.begin() + to + 1);
  for (int widening = 0; widening <= kMaxWidening && total.remaining > 0.0; ++widening) {
    const InsertionRelaxation attempt = relaxWindow(knots, integrals, axialStiffness, total.remaining, first - widening,
                                                    last + widening, rows, pointMasses, points);
    total.iterations += attempt.iterations;
    total.remaining = attempt.remaining;
  }
  for (int i = from; i <= to; ++i) {
    total.displacement = std::max(total.displacement,
                                  (points[static_cast<size_t>(i)] - start[static_cast<size_t>(i - from)]).norm());
  }
  return total;
}

}  // namespace rope
