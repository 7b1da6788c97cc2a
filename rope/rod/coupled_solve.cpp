// SPDX-License-Identifier: MIT
#include "rope/rod/coupled_solve.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include <Eigen/Eigenvalues>

#include "rope/common/error.h"
#include "rope/spline/bspline_basis.h"

namespace rope {

namespace {

// Checks s of couplings[k].<member>; the name is built only for the error (prepare runs every
// substep, and a name longer than the small-string buffer costs an allocation per coupling).
void requireParameterOn(const Rod& rod, std::size_t k, const char* member, double s) {
  // Finite first: an ordered comparison with NaN raises the trapped "invalid" exception.
  if (std::isfinite(s) && s >= rod.beginParameter() && s <= rod.endParameter()) return;
  const std::string name = "couplings[" + std::to_string(k) + "]." + member;
  requireFinite(name, s);
  throw InvalidArgument(name, formatValue(s), "must be within its rod's parameter range [" +
                                                  formatValue(rod.beginParameter()) + ", " +
                                                  formatValue(rod.endParameter()) + "]");
}

}  // namespace

size_t CoupledSolve::pointSlot(int rod, double s) const {
  // FNV-1a over the rod and the parameter's bits; linear probing in a table at most half full.
  const double key = s == 0.0 ? 0.0 : s;  // -0 and +0 are one point, as == says
  std::uint64_t bits = 0;
  std::memcpy(&bits, &key, sizeof bits);
  std::uint64_t hash = 1469598103934665603ull;
  for (const std::uint64_t word : {static_cast<std::uint64_t>(rod), bits}) {
    hash ^= word;
    hash *= 1099511628211ull;
  }
  const size_t mask = pointTable_.size() - 1;
  size_t slot = static_cast<size_t>(hash ^ (hash >> 29)) & mask;
  for (;; slot = (slot + 1) & mask) {
    const int p = pointTable_[slot];
    if (p < 0) return slot;
    const Point& point = points_[static_cast<size_t>(p)];
    if (point.rod == rod && point.s == s) return slot;
  }
}

int CoupledSolve::pointIndex(int rod, double s) {
  // The couplings' points, each once (two couplings may share one): by hash, not by a scan of the
  // points found so far, which was quadratic in the couplings (1 % of the 2 m pile's step).
  const size_t slot = pointSlot(rod, s);
  if (pointTable_[slot] >= 0) return pointTable_[slot];
  pointTable_[slot] = pointCount_;
  // Reuse a slot (and its response buffer) from an earlier step: no allocation in a steady state.
  if (pointCount_ == static_cast<int>(points_.size())) points_.emplace_back();
  Point& point = points_[static_cast<size_t>(pointCount_)];
  point.rod = rod;
  point.s = s;
  const KnotVector& knots = rods_[static_cast<size_t>(rod)]->knots();
  const int k = knots.findSpan(s);
  BasisValues basis;
  evaluateBasis(knots, k, s, 0, basis);
  point.first = k - knots.degree();
  point.count = knots.degree() + 1;
  for (int a = 0; a < point.count; ++a) point.basis[a] = basis.d[0][static_cast<size_t>(a)];
  return pointCount_++;
}

Vec3 CoupledSolve::pointValue(const Point& point, const PointList& field) {
  const Vec3* q = field.data() + point.first;
  Vec3 value = Vec3::Zero();
  for (int a = 0; a < point.count; ++a) value += point.basis[a] * q[a];
  return value;
}

void CoupledSolve::ensureResponse(Side& side) {
  if (side.hasResponse) return;
  side.hasResponse = true;
  const Rod& owner = *rods_[static_cast<size_t>(side.rod)];
  side.response.resize(static_cast<size_t>(9 * owner.controlPointCount()));
  double s[2];
  for (int j = 0; j < side.count; ++j) s[j] = points_[static_cast<size_t>(side.points[j])].s;
  owner.trialImpulseResponsesOnward(s, side.weights, side.count, side.response.data());
}

Eigen::Matrix3d CoupledSolve::zBlock(size_t k, size_t l) {
  // Z = J P J^T, block (k, l) = sum over the rods both couplings touch of J_k P J_l^T there.
  Eigen::Matrix3d z = Eigen::Matrix3d::Zero();
  for (size_t x = 2 * k; x < 2 * k + 2; ++x) {
    for (size_t y = 2 * l; y < 2 * l + 2; ++y) {
      if (sides_[x].rod >= 0 && sides_[x].rod == sides_[y].rod) z += sideResponse(sides_[x], sides_[y]);
    }
  }
  return z;
}

const Eigen::Matrix3d& CoupledSolve::zBlockCached(size_t k, size_t l) {
  const size_t m = couplings_.size();
  int& column = zColumn_[l];
  if (column < 0) {
    column = zColumns_++;
    const size_t needed = static_cast<size_t>(zColumns_) * m;
    if (zCache_.size() < needed) {
      zCache_.resize(needed);
      zKnown_.resize(needed);
    }
    std::fill(zKnown_.begin() + static_cast<std::ptrdiff_t>(needed - m),
              zKnown_.begin() + static_cast<std::ptrdiff_t>(needed), char{0});
  }
  const size_t at = static_cast<size_t>(column) * m + k;
  if (!zKnown_[at]) {
    zCache_[at] = zBlock(k, l);
    zKnown_[at] = 1;
  }
  return zCache_[at];
}

Eigen::Matrix3d CoupledSolve::sideResponse(Side& x, Side& y) {
  // J_x P J_y^T = (J_y P J_x^T)^T (P is symmetric): read the response of the side whose first control
  // point comes first, at the other's rows, which it covers (Rod::trialImpulseResponsesOnward).
  if (x.first < y.first) return sideResponse(y, x).transpose();
  ensureResponse(y);
  Eigen::Matrix3d z = Eigen::Matrix3d::Zero();
  const size_t n3 = y.response.size() / 3;
  for (int j = 0; j < x.count; ++j) {
    const Point& a = points_[static_cast<size_t>(x.points[j])];
    for (int column = 0; column < 3; ++column) {
      const double* r = &y.response[static_cast<size_t>(column) * n3];
      for (int i = 0; i < a.count; ++i) {
        const double weight = x.weights[j] * a.basis[i];
        const double* block = r + 3 * (a.first + i);
        z(0, column) += weight * block[0];
        z(1, column) += weight * block[1];
        z(2, column) += weight * block[2];
      }
    }
  }
  return z;
}

void CoupledSolve::prepare(const std::vector<Rod*>& rods, const std::vector<PointCoupling>& couplings) {
  for (size_t i = 0; i < rods.size(); ++i) {
    const auto name = [i] { return "rods[" + std::to_string(i) + "]"; };
    if (rods[i] == nullptr) throw InvalidArgument(name(), "null", "must be a rod");
    if (!rods[i]->hasTrial()) throw InvalidArgument(name(), "no trial", "solveTrial() must have succeeded");
  }
  const int rodCount = static_cast<int>(rods.size());
  for (size_t k = 0; k < couplings.size(); ++k) {
    const PointCoupling& c = couplings[k];
    const auto name = [k](const char* member) { return "couplings[" + std::to_string(k) + "]." + member; };
    if (c.rodA < 0 || c.rodA >= rodCount) throw InvalidArgument(name("rodA"), std::to_string(c.rodA), "no such rod");
    if (c.rodB < 0 || c.rodB >= rodCount) throw InvalidArgument(name("rodB"), std::to_string(c.rodB), "no such rod");
    requireParameterOn(*rods[static_cast<size_t>(c.rodA)], k, "sA", c.sA);
    requireParameterOn(*rods[static_cast<size_t>(c.rodB)], k, "sB", c.sB);
    if (c.rodA == c.rodB && c.sA == c.sB) throw InvalidArgument(name("sB"), formatValue(c.sB), "must differ from sA on the same rod");
  }

  rods_ = rods;
  couplings_ = couplings;
  pointCount_ = 0;
  const size_t m = couplings.size();
  size_t tableSize = 16;
  while (tableSize < 4 * m) tableSize *= 2;  // 2m points at most: at most half full
  pointTable_.assign(tableSize, -1);
  pointA_.resize(m);
  pointB_.resize(m);
  trialChange_.resize(m);
  if (sides_.size() < 2 * m) sides_.resize(2 * m);  // buffers kept: no allocation in a steady state
  for (size_t k = 0; k < m; ++k) {
    const PointCoupling& c = couplings[k];
    pointA_[k] = pointIndex(c.rodA, c.sA);
    pointB_[k] = pointIndex(c.rodB, c.sB);
    // The sides: +B(sA) on rod A and -B(sB) on rod B, one side when both are on one rod.
    Side& sideA = sides_[2 * k];
    Side& sideB = sides_[2 * k + 1];
    const int firstA = points_[static_cast<size_t>(pointA_[k])].first;
    const int firstB = points_[static_cast<size_t>(pointB_[k])].first;
    sideA.rod = c.rodA;
    sideA.points[0] = pointA_[k];
    sideA.weights[0] = 1.0;
    sideA.hasResponse = false;
    sideB.hasResponse = false;
    if (c.rodA == c.rodB) {
      sideA.points[1] = pointB_[k];
      sideA.weights[1] = -1.0;
      sideA.count = 2;
      sideA.first = std::min(firstA, firstB);
      sideB.rod = -1;
      sideB.count = 0;
    } else {
      sideA.count = 1;
      sideA.first = firstA;
      sideB.rod = c.rodB;
      sideB.points[0] = pointB_[k];
      sideB.weights[0] = -1.0;
      sideB.count = 1;
      sideB.first = firstB;
    }
    const Rod& a = *rods[static_cast<size_t>(c.rodA)];
    const Rod& b = *rods[static_cast<size_t>(c.rodB)];
    const Point& pa = points_[static_cast<size_t>(pointA_[k])];
    const Point& pb = points_[static_cast<size_t>(pointB_[k])];
    // The velocities at the points from their basis values (what Rod::trialVelocity and
    // Rod::velocity would evaluate again, in the same order: the same bits).
    trialChange_[k] = (pointValue(pa, a.trialVelocities()) - pointValue(pa, a.velocities())) -
                      (pointValue(pb, b.trialVelocities()) - pointValue(pb, b.velocities()));
  }

  acting_.clear();
  rootKnown_.assign(m, 0);
  rootOf_.resize(m);
  rootAdmittance_.resize(m);
  zColumn_.assign(m, -1);
  zColumns_ = 0;
  deltaImpulses_.assign(m, Vec3::Zero());  // no solve yet: solvedRelativeChange is the trial's change
  deltaValid_ = false;
}

bool CoupledSolve::solveImpulses(const std::vector<CouplingLaw>& laws, std::vector<Vec3>& impulses) {
  const size_t m = couplings_.size();
  if (laws.size() != m) {
    throw InvalidArgument("laws.size()", std::to_string(laws.size()), "must equal the coupling count " + std::to_string(m));
  }
  impulses.assign(m, Vec3::Zero());
  acting_.clear();
  deltaImpulses_.assign(m, Vec3::Zero());  // solvedRelativeChange's impulses: zero unless this solve succeeds
  deltaValid_ = false;
  for (size_t k = 0; k < m; ++k) {
    if (!laws[k].admittance.allFinite() || !laws[k].impulse.allFinite()) return false;
    if (laws[k].admittance.isZero(0.0) && laws[k].impulse.isZero(0.0)) continue;  // p_k = 0 exactly
    acting_.push_back(static_cast<int>(k));
  }
  const int a = static_cast<int>(acting_.size());
  if (a == 0) return true;
  // (I + W Z) p = e - W c over the acting couplings (c = J dv_trial), solved in its symmetric form:
  // with W = L L^T per coupling (L = V sqrt(Lambda) from W's eigenvectors; W is PSD),
  //   (I + L^T Z L) u = L^T (c + Z e),   p = e - L u,
  // whose matrix is symmetric positive definite (Z = J P J^T is PSD), so a Cholesky factor half the
  // cost of an LU suffices and cannot meet a zero pivot.
  roots_.resize(static_cast<size_t>(a));
  zActing_.resize(3 * a, 3 * a);
  impulse_.resize(3 * a);
  for (int i = 0; i < a; ++i) {
    const size_t k = static_cast<size_t>(acting_[static_cast<size_t>(i)]);
    // An active set asks again with most laws unchanged: their roots are kept (per coupling, since
    // prepare(); compared bit for bit), the same bits as computing them again.
    if (!rootKnown_[k] || std::memcmp(rootAdmittance_[k].data(), laws[k].admittance.data(), sizeof(Eigen::Matrix3d)) != 0) {
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(0.5 * (laws[k].admittance + laws[k].admittance.transpose()));
      rootOf_[k] = eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal();
      rootAdmittance_[k] = laws[k].admittance;
      rootKnown_[k] = 1;
    }
    roots_[static_cast<size_t>(i)] = rootOf_[k];
    impulse_.segment<3>(3 * i) = laws[k].impulse;
    for (int j = 0; j <= i; ++j) {
      const Eigen::Matrix3d block = zBlockCached(k, static_cast<size_t>(acting_[static_cast<size_t>(j)]));
      zActing_.block<3, 3>(3 * i, 3 * j) = block;
      zActing_.block<3, 3>(3 * j, 3 * i) = block.transpose();
    }
  }
  system_.setIdentity(3 * a, 3 * a);
  rhs_.noalias() = zActing_ * impulse_;
  for (int i = 0; i < a; ++i) {
    const size_t k = static_cast<size_t>(acting_[static_cast<size_t>(i)]);
    const Eigen::Matrix3d& li = roots_[static_cast<size_t>(i)];
    rhs_.segment<3>(3 * i) = li.transpose() * (trialChange_[k] + rhs_.segment<3>(3 * i));
    for (int j = 0; j <= i; ++j) {
      system_.block<3, 3>(3 * i, 3 * j) += li.transpose() * zActing_.block<3, 3>(3 * i, 3 * j) * roots_[static_cast<size_t>(j)];
    }
  }
  llt_.compute(system_);  // reads the lower triangle
  if (llt_.info() != Eigen::Success) return false;
  u_ = llt_.solve(rhs_);
  if (!u_.allFinite()) return false;
  p_ = impulse_;
  for (int i = 0; i < a; ++i) p_.segment<3>(3 * i) -= roots_[static_cast<size_t>(i)] * u_.segment<3>(3 * i);
  for (int i = 0; i < a; ++i) impulses[static_cast<size_t>(acting_[static_cast<size_t>(i)])] = p_.segment<3>(3 * i);
  deltaImpulses_ = impulses;
  return true;
}

Vec3 CoupledSolve::relativeChange(int k, const std::vector<Vec3>& impulses) {
  Vec3 change = trialChange_[static_cast<size_t>(k)];
  for (size_t l = 0; l < impulses.size(); ++l) {
    if (impulses[l].isZero(0.0)) continue;
    change += zBlockCached(static_cast<size_t>(k), l) * impulses[l];
  }
  return change;
}

Vec3 CoupledSolve::solvedRelativeChange(int k) {
  if (k < 0 || k >= size()) {
    throw InvalidArgument("k", std::to_string(k), "must index a coupling (0 to " + std::to_string(size() - 1) + ")");
  }
  // w_new - w = J_k (dv_trial + P J^T p) = trialChange_k + B_a dv - B_b dv (eq. 37).
  if (!deltaValid_) computeVelocityChange(deltaImpulses_);
  return trialChange_[static_cast<size_t>(k)] + velocityChangeAt(pointA_[static_cast<size_t>(k)]) -
         velocityChangeAt(pointB_[static_cast<size_t>(k)]);
}

void CoupledSolve::computeVelocityChange(const std::vector<Vec3>& impulses) {
  velocityChange_.resize(rods_.size());
  touched_.assign(rods_.size(), 0);
  for (size_t r = 0; r < rods_.size(); ++r) {
    velocityChange_[r].assign(static_cast<size_t>(3 * rods_[r]->controlPointCount()), 0.0);
  }
  // dv = P J^T p: the generalised impulses J^T p per rod, then one pinned solve per rod
  // (Rod::trialGeneralizedResponse), whatever the number of couplings.
  for (size_t l = 0; l < impulses.size() && l < couplings_.size(); ++l) {
    if (impulses[l].isZero(0.0)) continue;
    for (int side = 0; side < 2; ++side) {
      const Point& point = points_[static_cast<size_t>(side == 0 ? pointA_[l] : pointB_[l])];
      std::vector<double>& g = velocityChange_[static_cast<size_t>(point.rod)];
      touched_[static_cast<size_t>(point.rod)] = 1;
      const Vec3 p = side == 0 ? impulses[l] : Vec3(-impulses[l]);
      for (int i = 0; i < point.count; ++i) {
        double* block = &g[3 * static_cast<size_t>(point.first + i)];
        for (int axis = 0; axis < 3; ++axis) block[axis] += point.basis[i] * p[axis];
      }
    }
  }
  for (size_t r = 0; r < rods_.size(); ++r) {
    if (touched_[r]) rods_[r]->trialGeneralizedResponse(velocityChange_[r].data());
  }
  deltaValid_ = true;
}

Vec3 CoupledSolve::velocityChangeAt(int p) const {
  const Point& point = points_[static_cast<size_t>(p)];
  const std::vector<double>& dv = velocityChange_[static_cast<size_t>(point.rod)];
  Vec3 change = Vec3::Zero();
  for (int i = 0; i < point.count; ++i) {
    const double* block = &dv[3 * static_cast<size_t>(point.first + i)];
    change += point.basis[i] * Vec3(block[0], block[1], block[2]);
  }
  return change;
}

void CoupledSolve::apply(const std::vector<Vec3>& impulses) {
  if (impulses.size() != couplings_.size()) {
    throw InvalidArgument("impulses.size()", std::to_string(impulses.size()),
                          "must equal the coupling count " + std::to_string(couplings_.size()));
  }
  // dv = P J^T p per rod, the sum solvedRelativeChange reads: still the last solve's when these are
  // its impulses (an active set applies what it solved, then reads the slips once more), else it
  // describes no solve any more.
  if (!(deltaValid_ && impulses == deltaImpulses_)) {
    computeVelocityChange(impulses);
    deltaValid_ = impulses == deltaImpulses_;
  }
  for (size_t r = 0; r < rods_.size(); ++r) {
    Rod& rod = *rods_[r];
    if (!touched_[r]) continue;
    rod.correctTrial(velocityChange_[r].data());
    for (size_t k = 0; k < couplings_.size(); ++k) {
      if (impulses[k].isZero(0.0)) continue;  // a coupling that did not act needs no knot
      const PointCoupling& c = couplings_[k];
      if (!c.interaction) continue;
      if (c.rodA == static_cast<int>(r)) rod.markInteraction(c.sA);
      if (c.rodB == static_cast<int>(r)) rod.markInteraction(c.sB);
    }
  }
}

}  // namespace rope
