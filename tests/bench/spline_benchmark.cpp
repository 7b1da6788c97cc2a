// SPDX-License-Identifier: MIT
// Speed of the B-spline core's hot paths (cubic, n = 16 and n = 4096 control points):
// point evaluation of C, C', C''; the O(d) insertion plan; full insertion into a curve, whose
// std::vector storage shifts O(n) elements per insertion.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <vector>

#include "rope/spline/bspline_basis.h"
#include "rope/spline/bspline_curve.h"
#include "rope/spline/knot_insertion.h"

namespace {

using rope::BSplineCurve;
using rope::KnotVector;
using rope::PointList;
using rope::Vec3;

// A cubic helix-like curve on non-uniform knots with n control points.
BSplineCurve makeCurve(int n) {
  std::mt19937 rng(1234);
  std::uniform_real_distribution<double> gap(0.5, 1.5);
  std::vector<double> knots(4, 0.0);
  double s = 0.0;
  for (int i = 0; i < n - 4; ++i) knots.push_back(s += gap(rng));
  s += gap(rng);
  for (int i = 0; i < 4; ++i) knots.push_back(s);
  PointList points;
  for (int i = 0; i < n; ++i) points.push_back(Vec3(std::cos(0.3 * i), std::sin(0.3 * i), 0.05 * i));
  return BSplineCurve(KnotVector(3, knots), points);
}

// 1024 random parameters strictly inside the valid range, in random order.
std::vector<double> randomParameters(const BSplineCurve& curve) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> unit(1e-6, 1.0 - 1e-6);
  std::vector<double> s(1024);
  for (double& v : s) v = curve.beginParameter() + (curve.endParameter() - curve.beginParameter()) * unit(rng);
  return s;
}

void BM_EvaluatePoint(benchmark::State& state) {
  const BSplineCurve curve = makeCurve(static_cast<int>(state.range(0)));
  const std::vector<double> s = randomParameters(curve);
  size_t i = 0;
  for (auto _ : state) {
    rope::CurvePoint point = curve.evaluate(s[i++ & 1023u]);  // validates s, finds the span, C, C', C''
    benchmark::DoNotOptimize(point);
  }
}
BENCHMARK(BM_EvaluatePoint)->Arg(16)->Arg(4096);

void BM_EvaluatePosition(benchmark::State& state) {
  const BSplineCurve curve = makeCurve(static_cast<int>(state.range(0)));
  const std::vector<double> s = randomParameters(curve);
  size_t i = 0;
  for (auto _ : state) {
    Vec3 p = curve.position(s[i++ & 1023u]);
    benchmark::DoNotOptimize(p);
  }
}
BENCHMARK(BM_EvaluatePosition)->Arg(16)->Arg(4096);

void BM_EvaluateBasisHotPath(benchmark::State& state) {
  const BSplineCurve curve = makeCurve(static_cast<int>(state.range(0)));
  const std::vector<double> s = randomParameters(curve);
  rope::BasisValues basis;
  size_t i = 0;
  for (auto _ : state) {
    const double t = s[i++ & 1023u];
    rope::evaluateBasis(curve.knots(), curve.knots().findSpanUnchecked(t), t, 2, basis);
    benchmark::DoNotOptimize(basis);
  }
}
BENCHMARK(BM_EvaluateBasisHotPath)->Arg(16)->Arg(4096);

// Sorted batch of 1024 parameters (span reuse); reported per point.
void BM_EvaluateSortedBatch(benchmark::State& state) {
  const BSplineCurve curve = makeCurve(static_cast<int>(state.range(0)));
  std::vector<double> s = randomParameters(curve);
  std::sort(s.begin(), s.end());
  std::vector<rope::CurvePoint> out(s.size());
  for (auto _ : state) {
    curve.evaluate(s, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(s.size()));
}
BENCHMARK(BM_EvaluateSortedBatch)->Arg(16)->Arg(4096);

// The O(d) part of an insertion: validation, span search, multiplicity, the d coefficients.
void BM_PlanKnotInsertion(benchmark::State& state) {
  const BSplineCurve curve = makeCurve(static_cast<int>(state.range(0)));
  const std::vector<double> s = randomParameters(curve);
  size_t i = 0;
  for (auto _ : state) {
    rope::KnotInsertion plan = rope::planKnotInsertion(curve.knots(), s[i++ & 1023u]);
    benchmark::DoNotOptimize(plan);
  }
}
BENCHMARK(BM_PlanKnotInsertion)->Arg(16)->Arg(4096);

// Full BSplineCurve::insertKnot (plan + knot vector insert + control point insert). Each
// iteration restores the curve untimed, then times a batch of 8 insertions with a steady clock,
// so the curve grows from n to n+8 within a batch; the reported time is per insertion.
void BM_InsertKnot(benchmark::State& state) {
  const BSplineCurve original = makeCurve(static_cast<int>(state.range(0)));
  const std::vector<double> s = randomParameters(original);
  constexpr int kBatch = 8;
  BSplineCurve curve = original;
  size_t i = 0;
  for (auto _ : state) {
    curve = original;  // copy-assignment reuses the vectors' capacity
    const auto start = std::chrono::steady_clock::now();
    for (int b = 0; b < kBatch; ++b) {
      rope::KnotInsertion plan = curve.insertKnot(s[i++ & 1023u]);
      benchmark::DoNotOptimize(plan);
    }
    const auto stop = std::chrono::steady_clock::now();
    state.SetIterationTime(std::chrono::duration<double>(stop - start).count() / kBatch);
  }
}
BENCHMARK(BM_InsertKnot)->Arg(16)->Arg(4096)->UseManualTime();

// The same cost measured in CPU time, which a busy machine inflates less than the wall clock
// above: restoring the curve and inserting one knot, minus restoring alone (next benchmark).
void BM_RestoreAndInsertKnot(benchmark::State& state) {
  const BSplineCurve original = makeCurve(static_cast<int>(state.range(0)));
  const std::vector<double> s = randomParameters(original);
  BSplineCurve curve = original;
  size_t i = 0;
  for (auto _ : state) {
    curve = original;
    rope::KnotInsertion plan = curve.insertKnot(s[i++ & 1023u]);
    benchmark::DoNotOptimize(plan);
  }
}
BENCHMARK(BM_RestoreAndInsertKnot)->Arg(16)->Arg(4096);

void BM_RestoreOnly(benchmark::State& state) {
  const BSplineCurve original = makeCurve(static_cast<int>(state.range(0)));
  BSplineCurve curve = original;
  curve.insertKnot(0.5 * (original.beginParameter() + original.endParameter()));  // same capacity as above
  for (auto _ : state) {
    curve = original;
    benchmark::DoNotOptimize(curve.controlPoints().data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_RestoreOnly)->Arg(16)->Arg(4096);

}  // namespace
