// SPDX-License-Identifier: MIT
#pragma once
// Implicit point couplings between rods (rope self-contact and rope-rope contact), solved exactly on
// top of the rods' own implicit steps.
//
// Each rod r has solved its trial step (Rod::solveTrial): A_r dv_r = r_r with its pins held. A
// coupling k ties C_a(s_a) to C_b(s_b) (two rods, or two places on one rod) with an impulse p_k on a
// (and -p_k on b) over the step that follows a linearised law
//   p_k = e_k - W_k (w_k,new - w_k),   w = C'_a(s_a) - C'_b(s_b) velocity of a relative to b,
// with e_k (N s) the impulse at the start-of-step state and W_k (kg, symmetric positive semidefinite)
// = h^2 K_k + h D_k for a spring-damper K_k, D_k: the same backward-Euler linearisation the rod uses
// for its own forces, so the coupling is as implicit as the rope. The coupled system
//   (A + J^T W J) dv = r + J^T e,   J = [b_a(s_a) (x) I3, -b_b(s_b) (x) I3]
// breaks the band (s_a and s_b are far apart) but J^T W J has rank <= 3 per coupling, so it is solved
// by the Woodbury identity against the rods' existing factors: with P the pinned inverse of each A
// (Rod::trialImpulseResponse) and Z = J P J^T (3m x 3m),
//   (I + W Z) p = e - W J dv_trial,   dv = dv_trial + P J^T p.
// The small system is solved in its symmetric positive definite form (Cholesky; see
// solveImpulses). Only the couplings that act (a non-zero law) enter the dense solve, and only they
// need responses, computed when a coupling first acts: a candidate with a zero law has p = 0 exactly,
// yet relativeChange() still predicts its motion (so an active set can switch it on). Cost: 3 O(n)
// solves per acting coupling and rod it touches, P (B_a - B_b)^T for a coupling within one rod (each
// only over the rows from its earlier point on: Z's blocks read a response at the later of two
// couplings, P being symmetric), one O(n) solve per rod for dv, O(m a) for the predictions and O(a^3)
// for the dense solve (a acting couplings out of m); the rods' band and factor are untouched. Exactly
// momentum-conserving: the impulses are equal and opposite by construction.

#include <vector>

#include <Eigen/Core>
#include <Eigen/Cholesky>

#include "rope/common/types.h"
#include "rope/rod/rod.h"

namespace rope {

struct PointCoupling {
  int rodA = 0;      // index into the rods given to CoupledSolve::prepare
  double sA = 0.0;   // curve parameter on rod A
  int rodB = 0;      // may equal rodA (self-contact); then sB != sA
  double sB = 0.0;
  // Whether apply() makes both points interaction points (a knot there, [A] §4) when the coupling
  // acts. False for a quadrature sample of a distributed contact, which must not refine the rope.
  bool interaction = true;
};

struct CouplingLaw {
  Vec3 impulse = Vec3::Zero();                             // e, N s, on A at the start-of-step state
  Eigen::Matrix3d admittance = Eigen::Matrix3d::Zero();    // W = h^2 K + h D, kg, symmetric PSD
};

class CoupledSolve {
 public:
  // Sets up the couplings (basis values and trial motion of every point). Every rod must hold a trial
  // (Rod::solveTrial succeeded, nothing changed since). Throws InvalidArgument naming the coupling
  // ("couplings[k].rodA", "couplings[k].sB", ...) for an index outside rods or a parameter outside
  // its rod, and ("rods[i]") for a null rod or one without a trial; nothing is prepared then.
  void prepare(const std::vector<Rod*>& rods, const std::vector<PointCoupling>& couplings);
  int size() const { return static_cast<int>(couplings_.size()); }

  // Relative velocity change of coupling k in the trial, w_trial - w (m/s).
  const Vec3& trialRelativeChange(int k) const { return trialChange_[static_cast<size_t>(k)]; }

  // Solves for the impulses p (N s, on A) under the given laws (one per coupling, same order); a
  // coupling whose law is zero gets p = 0 and costs nothing in the solve. Returns false if the laws or
  // the result are not finite or the small system is singular; the impulses are then unspecified. Can
  // be called repeatedly with other laws (active sets, friction bounds): responses are kept.
  bool solveImpulses(const std::vector<CouplingLaw>& laws, std::vector<Vec3>& impulses);
  // The relative velocity change of coupling k at the end of the step with impulses p: w_new - w.
  // Not const: it fills the cache of Z blocks (see zBlockCached).
  Vec3 relativeChange(int k, const std::vector<Vec3>& impulses);
  // The same for the impulses of the last successful solveImpulses since prepare() (zero before one,
  // or after one that failed), at O(degree) per call after one O(a n) pass per solve: for an active
  // set that asks for every candidate after each solve. Throws InvalidArgument("k") outside
  // [0, size()).
  Vec3 solvedRelativeChange(int k);
  // Adds the impulses' effect to the rods' trials (Rod::correctTrial) and marks the coupling points as
  // interaction points (a knot there at commit, [A] §4).
  void apply(const std::vector<Vec3>& impulses);

 private:
  struct Point {
    int rod;
    double s;
    int first;              // first control point with b_i(s) != 0
    double basis[kMaxDegree + 1];
    int count;
  };
  // A coupling's part on one rod: the combination sum_j weight_j B(s_j) of its points there (one
  // point, or both with +1 and -1 where the coupling ties two places of one rod) and the rod's
  // response to it, P (sum_j weight_j B(s_j))^T: 3 columns of 3n, once needed, valid on the rows from
  // `first` on (Rod::trialImpulseResponsesOnward). One solve per coupling and rod where there was one
  // per point: a self-contact's solve runs from the earlier point on, and the later point's is saved.
  struct Side {
    int rod = -1;  // -1: unused (the second side of a coupling within one rod)
    int first = 0;  // the first control point any of its points touches
    int points[2] = {-1, -1};  // into points_
    double weights[2] = {0.0, 0.0};
    int count = 0;
    bool hasResponse = false;
    std::vector<double> response;
  };
  int pointIndex(int rod, double s);
  size_t pointSlot(int rod, double s) const;  // pointTable_'s slot of (rod, s): its point or empty
  static Vec3 pointValue(const Point& point, const PointList& field);  // sum_i b_i(s) field_i
  void ensureResponse(Side& side);
  // Y(x, y) = J_x P J_y^T for two sides on one rod, from the response of whichever side's first
  // control point comes first (computed on demand).
  Eigen::Matrix3d sideResponse(Side& x, Side& y);
  Eigen::Matrix3d zBlock(size_t k, size_t l);  // block (k, l) of Z
  // zBlock(k, l), computed once per prepare(): an active-set loop asks for the same blocks in every
  // pass (relativeChange of each candidate against each acting coupling was 16 % of the 2 m pile's
  // step, computed 3.4 times over). The reference is valid until the next call.
  const Eigen::Matrix3d& zBlockCached(size_t k, size_t l);

  std::vector<Rod*> rods_;
  std::vector<PointCoupling> couplings_;
  std::vector<Point> points_;  // the first pointCount_ are in use; the rest keep their buffers
  int pointCount_ = 0;
  std::vector<int> pointTable_;  // open addressing by (rod, s): index into points_, -1 empty
  std::vector<int> pointA_, pointB_;  // per coupling
  std::vector<Side> sides_;  // per coupling k: sides_[2k] and sides_[2k + 1]; buffers kept between prepares
  std::vector<Vec3> trialChange_;
  // The cache of zBlockCached, one column of m blocks per coupling l that has been asked for (those
  // that acted): zColumn_[l] is its column, -1 none yet. Buffers only grow (no allocation in a
  // steady state).
  std::vector<int> zColumn_;
  int zColumns_ = 0;
  std::vector<Eigen::Matrix3d> zCache_;  // column * m + k
  std::vector<char> zKnown_;             // same layout: whether the block was computed
  std::vector<int> acting_;  // couplings with a non-zero law in the last solveImpulses
  Eigen::MatrixXd system_;   // I + L^T Z L over the acting couplings (lower triangle)
  Eigen::MatrixXd zActing_;  // Z over the acting couplings
  Eigen::VectorXd rhs_, impulse_;
  Eigen::VectorXd u_, p_;  // the solve's u and p (kept: no allocation while the acting count stays)
  std::vector<Eigen::Matrix3d> roots_;  // L with W = L L^T, per acting coupling
  // Per coupling: the last admittance whose root was computed since prepare(), and that root.
  std::vector<Eigen::Matrix3d> rootOf_, rootAdmittance_;
  std::vector<char> rootKnown_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  // Every rod's velocity change dv = P J^T p for the impulses (per rod 3n, m/s), and which rods it
  // touches: the correction apply() makes, and what solvedRelativeChange reads for the last solve's
  // impulses (one O(a n) sum per solve, then O(degree) per coupling, instead of a 3x3 block of Z per
  // candidate and acting coupling: 12 % of the 2 m pile's step). For the last solve while deltaValid_.
  void computeVelocityChange(const std::vector<Vec3>& impulses);
  Vec3 velocityChangeAt(int p) const;  // B_p dv at point p
  std::vector<std::vector<double>> velocityChange_;
  std::vector<char> touched_;  // per rod: some acting coupling point lies on it
  std::vector<Vec3> deltaImpulses_;
  bool deltaValid_ = false;
};

}  // namespace rope
