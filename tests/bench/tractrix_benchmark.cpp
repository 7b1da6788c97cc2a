// SPDX-License-Identifier: MIT
// Tractrix kinematics: [B] §4's whole 52-step planar experiment per variant, and one chain pass
// per segment for chains of 20 .. 10,000 segments (docs/method.md §13: O(n)).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>

#include "demos/scenes/arc_path.h"
#include "rope/tractrix/tractrix_chain.h"
#include "rope/tractrix/tractrix_rope.h"

namespace {

using rope::PointList;
using rope::Vec3;

// The S-bend of the experiment test (demos/scenes/arc_path.h): 52 targets 0.5 m apart.
PointList experimentTargets() {
  const rope::demos::ArcPath path = rope::demos::sBendPath();
  PointList targets;
  for (int k = 1; k <= 52; ++k) targets.push_back(path.at(0.5 * k));
  return targets;
}

// Construction (interpolation of the 5 m straight object) plus the 52 steps, as a user would run it.
void runExperiment(benchmark::State& state, rope::TractrixVariant variant, int segments,
                   rope::TractrixLengthCorrection correction = rope::TractrixLengthCorrection::kRestoreCurveLength) {
  const PointList targets = experimentTargets();
  const PointList shape = {Vec3(0, 0, 0), Vec3(-5, 0, 0)};
  rope::TractrixSettings settings;
  settings.variant = variant;
  settings.segmentCount = segments;
  settings.lengthCorrection = correction;
  settings.maxControlPoints = std::max(settings.maxControlPoints, 4 * segments);
  int maxCount = 0;
  for (auto _ : state) {
    rope::TractrixRope rope(shape, settings);
    for (const Vec3& target : targets) {
      const rope::TractrixStepReport& report = rope.moveLeadingEnd(target);
      maxCount = std::max(maxCount, report.controlPointCount);
    }
    benchmark::DoNotOptimize(rope.controlPoints().data());
  }
  state.counters["max_control_points"] = maxCount;
}

void BM_Experiment52Steps_TRX_SD_MRG(benchmark::State& state) {
  runExperiment(state, rope::TractrixVariant::kSplineSubdivideMerge, 6);
}
// [B] as published (no length correction): the correction's cost is the difference.
void BM_Experiment52Steps_TRX_SD_MRG_AsPublished(benchmark::State& state) {
  runExperiment(state, rope::TractrixVariant::kSplineSubdivideMerge, 6, rope::TractrixLengthCorrection::kNone);
}
// The same with n initial sides, with and without the correction: both stay O(n) per step.
void BM_Experiment52Steps_TRX_SD_MRG_Sides(benchmark::State& state) {
  runExperiment(state, rope::TractrixVariant::kSplineSubdivideMerge, static_cast<int>(state.range(0)));
}
void BM_Experiment52Steps_TRX_SD_MRG_Sides_AsPublished(benchmark::State& state) {
  runExperiment(state, rope::TractrixVariant::kSplineSubdivideMerge, static_cast<int>(state.range(0)),
                rope::TractrixLengthCorrection::kNone);
}
void BM_Experiment52Steps_TRX_SD(benchmark::State& state) {
  runExperiment(state, rope::TractrixVariant::kSplineSubdivide, 6);
}
void BM_Experiment52Steps_TRX_20(benchmark::State& state) {
  runExperiment(state, rope::TractrixVariant::kPolyline, 20);
}
BENCHMARK(BM_Experiment52Steps_TRX_SD_MRG)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Experiment52Steps_TRX_SD_MRG_AsPublished)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Experiment52Steps_TRX_SD_MRG_Sides)->Arg(60)->Arg(600)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Experiment52Steps_TRX_SD_MRG_Sides_AsPublished)->Arg(60)->Arg(600)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Experiment52Steps_TRX_SD)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Experiment52Steps_TRX_20)->Unit(benchmark::kMicrosecond);

// One chain pass over n segments of 0.1 m. The chain lies along -x and the leading end wobbles
// while advancing along +x, so the displacement does not die out: every segment moves every pass
// (checked after timing) and the time per segment is the real per-segment cost.
void BM_ChainPass(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  PointList points;
  for (int i = 0; i <= n; ++i) points.emplace_back(-0.1 * i, 0.0, 0.0);
  const std::vector<double> lengths(static_cast<size_t>(n), 0.1);
  Vec3 leading = points[0];
  long pass = 0;
  bool tailMovedEveryPass = true;
  for (auto _ : state) {
    ++pass;
    leading += Vec3(0.02, 0.01 * std::sin(0.05 * pass), 0.005 * std::cos(0.07 * pass));
    const Vec3 tail = points.back();
    rope::tractrixChainPass(points, lengths, leading);
    tailMovedEveryPass = tailMovedEveryPass && !(points.back() == tail);
    benchmark::DoNotOptimize(points.data());
  }
  state.SetItemsProcessed(state.iterations() * n);
  state.counters["ns_per_segment"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * n, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["tail_moved_every_pass"] = tailMovedEveryPass ? 1 : 0;
}
BENCHMARK(BM_ChainPass)->Arg(20)->Arg(100)->Arg(1000)->Arg(10000);

}  // namespace
