// SPDX-License-Identifier: MIT
#include "rope/rod/rod_integrals.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>

#include "rope/common/error.h"
#include "rope/common/prefetch.h"
#include "rope/spline/bspline_basis.h"
#include "rope/spline/gauss_legendre.h"

namespace rope {

namespace {
// Offsets inside one span record.
struct Layout {
  int local, gauss;  // gauss: stretching slots per span
  int dBasis() const { return 2; }
  int w0() const { return dBasis() + gauss * local; }
  int w1() const { return w0() + gauss; }
  int w3() const { return w1() + gauss; }
  int mass() const { return w3() + gauss; }
  int bending() const { return mass() + local * local; }
  int curvature() const { return bending() + local * local; }
  int gravity() const { return curvature() + local * local; }
  int stride() const { return gravity() + local; }
};
}  // namespace

int RodIntegrals::exactGaussCount(int degree) {
  // Stretching: degree 4(d-1) -> 2d-1 points; mass: degree 2d -> d+1 points.
  return std::max(2 * degree - 1, degree + 1);
}

void RodIntegrals::touch() {
  // Process-wide, so that no two states of any two RodIntegrals share a revision (a copy shares its
  // source's until one of them changes).
  static std::atomic<std::uint64_t> counter{0};
  revision_ = ++counter;
}

void RodIntegrals::build(const KnotVector& knots, const PointList& restPoints, double linearDensity,
                         double bendingStiffness, int gaussCount, StretchingQuadrature stretching) {
  degree_ = knots.degree();
  gaussCount_ = gaussCount;
  stretching_ = stretching;
  // The locking-free rule uses at most d points in a span (a rod with a single span).
  stretchSlots_ = stretching == StretchingQuadrature::kExact ? gaussCount : degree_;
  linearDensity_ = linearDensity;
  bendingStiffness_ = bendingStiffness;
  const Layout layout{degree_ + 1, stretchSlots_};
  stride_ = layout.stride();
  spanCount_ = knots.controlPointCount() - degree_;
  data_.assign(static_cast<size_t>(spanCount_) * static_cast<size_t>(stride_), 0.0);
  for (int j = 0; j < spanCount_; ++j) computeSpan(knots, restPoints, j);
  balanceReducedWeights(knots);
  touch();
}

void RodIntegrals::computeSpan(const KnotVector& knots, const PointList& restPoints, int j) {
  const int d = degree_;
  const int local = d + 1;
  const Layout layout{local, stretchSlots_};
  double* record = spanData(j);
  std::fill(record, record + stride_, 0.0);
  const int k = d + j;
  const double s0 = knots[k];
  const double s1 = knots[k + 1];
  if (!(s1 > s0)) return;  // empty span: no contribution
  const double half = 0.5 * (s1 - s0);
  const double mid = 0.5 * (s0 + s1);
  BasisValues basis;
  // l0'(s) = |C0'(s)| from the rest curve.
  auto restSpeed = [&](double s) {
    evaluateBasis(knots, k, s, 2, basis);
    Vec3 restTangent = Vec3::Zero();
    for (int a = 0; a < local; ++a)
      restTangent += basis.d[1][static_cast<size_t>(a)] * restPoints[static_cast<size_t>(j + a)];
    const double l0 = restTangent.norm();
    if (!std::isfinite(l0) || l0 <= 0.0) {
      throw InvalidArgument("restPoints", "span " + std::to_string(j),
                            "rest curve must be regular (|C0'(s)| > 0)");
    }
    return l0;
  };

  // Mass ([A] eq. 10, linear density per rest length), gravity weights, bending and rest length.
  const GaussRule rule = gaussLegendre(gaussCount_);
  double restLength = 0.0;
  for (int g = 0; g < gaussCount_; ++g) {
    const double l0 = restSpeed(mid + half * rule.nodes[g]);
    const double w0 = rule.weights[g] * half * l0;
    const double w3 = rule.weights[g] * half / (l0 * l0 * l0);
    restLength += w0;
    for (int a = 0; a < local; ++a) {
      const double ba = basis.d[0][static_cast<size_t>(a)];
      const double ca = basis.d[2][static_cast<size_t>(a)];
      record[layout.gravity() + a] += linearDensity_ * w0 * ba;
      for (int b = 0; b < local; ++b) {
        record[layout.mass() + a * local + b] += linearDensity_ * w0 * ba * basis.d[0][static_cast<size_t>(b)];
        record[layout.bending() + a * local + b] += bendingStiffness_ * w3 * ca * basis.d[2][static_cast<size_t>(b)];
        record[layout.curvature() + a * local + b] += w3 * ca * basis.d[2][static_cast<size_t>(b)];
      }
    }
  }
  record[0] = restLength;

  // Stretching points (see StretchingQuadrature in rod_settings.h).
  int count = gaussCount_;
  if (stretching_ == StretchingQuadrature::kLockingFree) {
    const int extra = d - 1;
    count = 1 + (j == 0 ? extra / 2 : 0) + (j == spanCount_ - 1 ? extra - extra / 2 : 0);
  }
  const GaussRule stretchRule = gaussLegendre(count);
  for (int g = 0; g < count; ++g) {
    const double l0 = restSpeed(mid + half * stretchRule.nodes[g]);
    const double wj = stretchRule.weights[g] * half;
    record[layout.w0() + g] = wj * l0;
    record[layout.w1() + g] = wj / l0;
    record[layout.w3() + g] = wj / (l0 * l0 * l0);
    double* db = record + layout.dBasis() + g * local;
    for (int a = 0; a < local; ++a) db[a] = basis.d[1][static_cast<size_t>(a)];
  }
  record[1] = count;
}

void RodIntegrals::recomputeRange(const KnotVector& knots, const PointList& restPoints, int firstSpanK,
                                  int lastSpanK) {
  const int first = std::max(0, firstSpanK - degree_);
  const int last = std::min(spanCount_ - 1, lastSpanK - degree_);
  for (int j = first; j <= last; ++j) computeSpan(knots, restPoints, j);
}

void RodIntegrals::afterInsertion(const KnotInsertion& plan, const KnotVector& knots,
                                  const PointList& restPoints) {
  // Old span k became new spans k and k+1; old spans > k shift by one. The basis functions that
  // changed (new b_{k-d} .. b_{k+1}) touch new spans k-d .. k+d+1: recompute those, keep the rest.
  const int k = plan.span;
  const size_t at = static_cast<size_t>(k - degree_) * static_cast<size_t>(stride_);
  data_.insert(data_.begin() + static_cast<std::ptrdiff_t>(at), static_cast<size_t>(stride_), 0.0);
  ++spanCount_;
  recomputeRange(knots, restPoints, k - degree_ - 1, k + degree_ + 2);
  balanceReducedWeights(knots);
  touch();
}

void RodIntegrals::afterRemoval(const KnotRemoval& plan, const KnotVector& knots,
                                const PointList& restPoints) {
  // The removed knot index r separated old spans r-1 and r; they merge into new span r-1.
  const int r = plan.knotIndex;
  const int erased = std::clamp(r - degree_, 0, spanCount_ - 1);
  const size_t at = static_cast<size_t>(erased) * static_cast<size_t>(stride_);
  data_.erase(data_.begin() + static_cast<std::ptrdiff_t>(at),
              data_.begin() + static_cast<std::ptrdiff_t>(at + static_cast<size_t>(stride_)));
  --spanCount_;
  recomputeRange(knots, restPoints, r - degree_ - 2, r + degree_ + 1);
  balanceReducedWeights(knots);
  touch();
}

void RodIntegrals::balanceReducedWeights(const KnotVector& knots) {
  if (stretching_ != StretchingQuadrature::kLockingFree) return;
  const int d = degree_;
  const Layout layout{d + 1, stretchSlots_};
  using Node = BalanceNode;  // in order of s
  std::vector<Node>& nodes = nodeScratch_;
  nodes.clear();
  for (int j = 0; j < spanCount_; ++j) {
    const int count = static_cast<int>(spanData(j)[1]);
    if (count == 0) continue;
    const double s0 = knots[d + j];
    const double s1 = knots[d + j + 1];
    const GaussRule rule = gaussLegendre(count);
    for (int g = 0; g < count; ++g)
      nodes.push_back({j, g, 0.5 * (s0 + s1) + 0.5 * (s1 - s0) * rule.nodes[g], 0.5 * (s1 - s0) * rule.weights[g]});
  }
  // Rescales point (j, g) to weight w (W0, W1, W3 are all proportional to it).
  auto setWeight = [&](const Node& node, double w) {
    double* record = spanData(node.span);
    double& w0 = record[layout.w0() + node.point];
    double& w1 = record[layout.w1() + node.point];
    double& w3 = record[layout.w3() + node.point];
    const double factor = w / std::sqrt(w0 * w1);
    w0 *= factor;
    w1 *= factor;
    w3 *= factor;
  };
  auto fallBack = [&] {
    for (const Node& node : nodes) setWeight(node, node.plain);
  };
  // The derivative space: degree d-1 on the knots without their first and last entry.
  const int size = static_cast<int>(nodes.size());
  if (d < 2 || size != knots.controlPointCount() - 1) return fallBack();
  const std::vector<double>& values = knots.values();
  std::vector<double> trimmed(values.begin() + 1, values.end() - 1);
  // A knot of multiplicity d inside makes the derivative space discontinuous there: keep plain weights.
  for (size_t i = 0; i + static_cast<size_t>(d) - 1 < trimmed.size(); ++i) {
    const bool interior = trimmed[i] > knots.validBegin() && trimmed[i] < knots.validEnd();
    if (interior && trimmed[i] == trimmed[i + static_cast<size_t>(d) - 1]) return fallBack();
  }
  const KnotVector derivative(d - 1, std::move(trimmed));
  // Banded system sum_c N_j(x_c) w_c = int N_j ds, j, c = 0 .. size-1, half width W; the collocation
  // matrix of B-splines at interlacing nodes is totally positive, so elimination needs no pivoting.
  const int W = d + 1;
  const int stride = 2 * W + 1;
  std::vector<double>& band = bandScratch_;
  std::vector<double>& rhs = rhsScratch_;
  band.assign(static_cast<size_t>(size) * static_cast<size_t>(stride), 0.0);
  rhs.resize(static_cast<size_t>(size));
  auto at = [&](int row, int col) -> double& {
    return band[static_cast<size_t>(row) * static_cast<size_t>(stride) + static_cast<size_t>(col - row + W)];
  };
  for (int j = 0; j < size; ++j) rhs[static_cast<size_t>(j)] = (derivative[j + d] - derivative[j]) / d;
  BasisValues basis;
  for (int c = 0; c < size; ++c) {
    const Node& node = nodes[static_cast<size_t>(c)];
    const int span = node.span + d - 1;  // the span in the derivative knots
    evaluateBasis(derivative, span, node.s, 0, basis);
    for (int a = 0; a < d; ++a) {
      const int row = span - (d - 1) + a;
      if (std::abs(row - c) > W) return fallBack();
      at(row, c) = basis.d[0][static_cast<size_t>(a)];
    }
  }
  for (int p = 0; p < size; ++p) {
    const double pivot = at(p, p);
    if (!(std::abs(pivot) > 1e-12)) return fallBack();
    for (int r = p + 1; r <= std::min(size - 1, p + W); ++r) {
      const double factor = at(r, p) / pivot;
      if (factor == 0.0) continue;
      for (int c = p; c <= std::min(size - 1, p + W); ++c) at(r, c) -= factor * at(p, c);
      rhs[static_cast<size_t>(r)] -= factor * rhs[static_cast<size_t>(p)];
    }
  }
  for (int p = size - 1; p >= 0; --p) {
    double sum = rhs[static_cast<size_t>(p)];
    for (int c = p + 1; c <= std::min(size - 1, p + W); ++c) sum -= at(p, c) * rhs[static_cast<size_t>(c)];
    rhs[static_cast<size_t>(p)] = sum / at(p, p);
  }
  for (int c = 0; c < size; ++c) {
    const double w = rhs[static_cast<size_t>(c)];
    if (!std::isfinite(w) || w <= 0.0) return fallBack();
  }
  for (int c = 0; c < size; ++c) setWeight(nodes[static_cast<size_t>(c)], rhs[static_cast<size_t>(c)]);
}

SpanView RodIntegrals::span(int j) const {
  const Layout layout{degree_ + 1, stretchSlots_};
  const double* record = spanData(j);
  SpanView view;
  view.localCount = degree_ + 1;
  view.gaussCount = static_cast<int>(record[1]);
  view.restLength = record[0];
  view.dBasis = record + layout.dBasis();
  view.w0 = record + layout.w0();
  view.w1 = record + layout.w1();
  view.w3 = record + layout.w3();
  view.mass = record + layout.mass();
  view.bending = record + layout.bending();
  view.curvature = record + layout.curvature();
  view.gravity = record + layout.gravity();
  return view;
}

double RodIntegrals::B2(int i, int m) const {
  double sum = 0.0;
  const int lo = std::min(i, m);
  const int hi = std::max(i, m);
  for (int j = std::max(0, hi - degree_); j <= std::min(lo, spanCount_ - 1); ++j) {
    const SpanView v = span(j);
    for (int g = 0; g < v.gaussCount; ++g) {
      const double* db = v.dBasis + g * v.localCount;
      sum += v.w1[g] * db[i - j] * db[m - j];
    }
  }
  return sum;
}

double RodIntegrals::B4(int i, int m, int p, int q) const {
  double sum = 0.0;
  const int lo = std::min(std::min(i, m), std::min(p, q));
  const int hi = std::max(std::max(i, m), std::max(p, q));
  for (int j = std::max(0, hi - degree_); j <= std::min(lo, spanCount_ - 1); ++j) {
    const SpanView v = span(j);
    for (int g = 0; g < v.gaussCount; ++g) {
      const double* db = v.dBasis + g * v.localCount;
      sum += v.w3[g] * db[i - j] * db[m - j] * db[p - j] * db[q - j];
    }
  }
  return sum;
}

void RodIntegrals::prefetch() const { prefetchVector(data_); }

}  // namespace rope
