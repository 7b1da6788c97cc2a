// SPDX-License-Identifier: MIT
#pragma once
// The rod's constant integrals (docs/method.md §5–§7, [A] eqs. 10–12 and §4.2), kept per knot span so that
// storage is linear in n and a knot insertion or removal recomputes only the O(d) spans it touches.
//
// Rest metric: l0'(s) = |C0'(s)| of a rest curve C0 that is refined with the same knot plans as the
// state, so the material (mass, rest length, stiffness distribution) is a property of s alone and never
// of the resolution ([A] §3.2; docs/method.md §5, eq. 10).
//
// Per span and stretching quadrature point g (weight w_g, Jacobian J = span length / 2) we store
//   b'_a(s_g) for the d+1 non-zero basis functions, W1_g = w_g J / l0'(s_g), W3_g = w_g J / l0'(s_g)^3.
// These are the stretching integrals of docs/method.md §6 (eq. 15) in factored form:
//   B_im   = sum_g W1_g b'_i b'_m,    B_impq = sum_g W3_g b'_i b'_m b'_p b'_q,
// i.e. exactly the Gauss–Legendre value of the integrals (exact when l0' is constant: the quartic
// product has degree 4(d-1) and 2d-1 points integrate degree 4d-3). Contracting the factored form costs
// O(G d) per span instead of O(d^4), and it gives the strain at each point, which the Gauss–Newton
// clamp of the stiffness needs (method §6, eq. 17). B2()/B4() rebuild the tensor entries for tests.
// Also per span: the local mass matrix mu int b_a b_b l0' ds ([A] eq. 10), the local bending matrix
// EI int b_a'' b_b'' / l0'^3 ds (bending_energy.h), the same with EI = 1, the gravity weights mu int b_a l0' ds and the rest
// length int l0' ds.
// Not API: installed only because rope/rod/rod.h holds the integrals; it may change in any release.

#include <cstdint>
#include <vector>

#include "rope/common/types.h"
#include "rope/rod/rod_settings.h"
#include "rope/spline/knot_insertion.h"
#include "rope/spline/knot_removal.h"
#include "rope/spline/knot_vector.h"

namespace rope {

// Span j (knot span k = d + j) carries the basis functions b_j .. b_{j+d}.
struct SpanView {
  int localCount = 0;          // d + 1
  int gaussCount = 0;          // stretching points in this span (0 for an empty span)
  double restLength = 0.0;     // m
  const double* dBasis = nullptr;   // [g * localCount + a] = b'_a(s_g)
  const double* w0 = nullptr;       // [g] = w_g J l0'      (sums to the rest length)
  const double* w1 = nullptr;       // [g] = w_g J / l0'
  const double* w3 = nullptr;       // [g] = w_g J / l0'^3
  const double* mass = nullptr;     // [a * localCount + b], kg
  const double* bending = nullptr;  // [a * localCount + b], N/m
  const double* curvature = nullptr;  // [a * localCount + b], 1/m^3: bending with EI = 1 (adaptivity's
                                      // shape measure, defined also for a rope without bending stiffness)
  const double* gravity = nullptr;  // [a], kg
};

class RodIntegrals {
 public:
  void prefetch() const;  // cache hints for the cached integrals (rope/common/prefetch.h)
  // Minimal Gauss count that is exact for every integrand when l0' is constant.
  static int exactGaussCount(int degree);

  RodIntegrals() = default;
  // Computes every span. restPoints must match knots; linearDensity kg/m, bendingStiffness N m^2;
  // gaussCount points per span (exact for every integrand when l0' is constant: see exactGaussCount);
  // the stretching points follow `stretching` (see rod_settings.h). Throws InvalidArgument("restPoints", ...) if the rest curve is not regular
  // (l0' <= 0 somewhere).
  void build(const KnotVector& knots, const PointList& restPoints, double linearDensity,
             double bendingStiffness, int gaussCount,
             StretchingQuadrature stretching = StretchingQuadrature::kExact);
  // After insertion (knots/restPoints already updated with plan): O(d) spans recomputed.
  void afterInsertion(const KnotInsertion& plan, const KnotVector& knots, const PointList& restPoints);
  // After removal of the knot at plan.knotIndex (old numbering): O(d) spans recomputed.
  void afterRemoval(const KnotRemoval& plan, const KnotVector& knots, const PointList& restPoints);

  // Changes (to a value no other RodIntegrals in the process has had) whenever the integrals change:
  // build, afterInsertion, afterRemoval. Lets a caller keep results computed from them (Rod's
  // assembly cache) and know when they are stale.
  std::uint64_t revision() const { return revision_; }

  int degree() const { return degree_; }
  int gaussCount() const { return gaussCount_; }
  StretchingQuadrature stretchingQuadrature() const { return stretching_; }
  int spanCount() const { return spanCount_; }
  // Span j is the knot span k = degree + j.
  SpanView span(int j) const;
  double linearDensity() const { return linearDensity_; }
  double bendingStiffness() const { return bendingStiffness_; }

  // The tensor entries of docs/method.md eq. 15 rebuilt from the factored form (tests, diagnostics; O(n)).
  double B2(int i, int m) const;
  double B4(int i, int m, int p, int q) const;

 private:
  void computeSpan(const KnotVector& knots, const PointList& restPoints, int j);
  double* spanData(int j) { return &data_[static_cast<size_t>(j) * static_cast<size_t>(stride_)]; }
  const double* spanData(int j) const {
    return &data_[static_cast<size_t>(j) * static_cast<size_t>(stride_)];
  }
  void recomputeRange(const KnotVector& knots, const PointList& restPoints, int firstSpanK, int lastSpanK);
  // kLockingFree: re-weights the n-1 reduced points so that the rule integrates the whole derivative
  // space (degree d-1 splines) exactly, which makes a uniform strain exact on any knots (patch test).
  // Falls back to plain Gauss weights if the system is singular or a weight is not positive. O(n).
  void balanceReducedWeights(const KnotVector& knots);

  void touch();  // revision_ <- a new process-wide value

  std::uint64_t revision_ = 0;
  int degree_ = 3;
  int gaussCount_ = 0;
  int stretchSlots_ = 0;  // stretching points reserved per span
  StretchingQuadrature stretching_ = StretchingQuadrature::kExact;
  int spanCount_ = 0;
  int stride_ = 0;
  double linearDensity_ = 0.0;
  double bendingStiffness_ = 0.0;
  std::vector<double> data_;
  struct BalanceNode {
    int span, point;
    double s, plain;  // parameter and plain Gauss weight
  };
  std::vector<BalanceNode> nodeScratch_;
  std::vector<double> bandScratch_, rhsScratch_;
};

}  // namespace rope
