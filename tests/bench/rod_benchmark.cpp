// SPDX-License-Identifier: MIT
// One rod step (stretching + bending + gravity + two pins + the adaptivity check) for n control points.
// The counts are pinned (min = max = n) so that every iteration times the same n; the adaptivity
// criteria are still evaluated each step.
#include <benchmark/benchmark.h>

#include <algorithm>

#include "rope/rod/banded_matrix.h"
#include "rope/rod/rod.h"

namespace {

rope::Rod makeRope(int n, rope::TimeIntegrator integrator = rope::TimeIntegrator::kBdf2) {
  rope::RodSettings settings;
  settings.timeIntegrator = integrator;
  settings.restLength = 1.0;
  settings.initialControlPoints = n;
  settings.minControlPoints = n;
  settings.maxControlPoints = n;
  settings.massDamping = 1.0;
  rope::Rod rod = rope::Rod::fromSegment(settings, rope::Vec3(0, 0, 0), rope::Vec3(1, 0, 0));
  rod.pin(0.0);
  rod.pin(1.0, rope::Vec3(0.9, 0, 0));  // slack: the rope sags and moves
  for (int i = 0; i < 20; ++i) rod.step(1.0 / 240);
  return rod;
}

// Steps a rope of state.range(0) control points with the given integrator.
void stepRope(benchmark::State& state, rope::TimeIntegrator integrator) {
  const int n = static_cast<int>(state.range(0));
  rope::Rod rod = makeRope(n, integrator);
  for (auto _ : state) {
    const rope::StepReport report = rod.step(1.0 / 240);
    benchmark::DoNotOptimize(report.controlPoints);
    if (!report.ok) state.SkipWithError(report.failure);
  }
  state.SetComplexityN(n);
  state.counters["n"] = n;
}

void BM_RodStep(benchmark::State& state) { stepRope(state, rope::TimeIntegrator::kBdf2); }
BENCHMARK(BM_RodStep)->RangeMultiplier(4)->Range(16, 4096)->Complexity(benchmark::oN)->Unit(benchmark::kMicrosecond);

// The same step with backward Euler, for the cost of BDF2's history (the default above) in one run.
void BM_RodStepBackwardEuler(benchmark::State& state) { stepRope(state, rope::TimeIntegrator::kBackwardEuler); }
BENCHMARK(BM_RodStepBackwardEuler)->RangeMultiplier(4)->Range(16, 4096)->Complexity(benchmark::oN)->Unit(benchmark::kMicrosecond);

// Factorises the rod's system shape (3 x 3 blocks, block half bandwidth 3: w = 11) of state.range(0)
// control points, a diagonally dominant band refilled before each factorisation (refill included).
void BM_BandedFactorize(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  rope::SymmetricBandedMatrix matrix;
  matrix.reset(n, 3, 3);
  const int w = matrix.halfBandwidth();
  for (int r = 0; r < matrix.size(); ++r)
    for (int c = std::max(0, r - w); c <= r; ++c) matrix.at(r, c) = r == c ? 4.0 * w : 1.0 / (1 + r - c + (r % 7));
  const rope::SymmetricBandedMatrix original = matrix;
  for (auto _ : state) {
    matrix = original;
    const bool ok = matrix.factorize();
    benchmark::DoNotOptimize(ok);
    if (!ok) state.SkipWithError("not positive definite");
  }
  state.SetComplexityN(n);
}
BENCHMARK(BM_BandedFactorize)->RangeMultiplier(4)->Range(16, 1024)->Complexity(benchmark::oN)->Unit(benchmark::kMicrosecond);

}  // namespace
