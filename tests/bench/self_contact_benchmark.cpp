// SPDX-License-Identifier: MIT
// Cost of self-contact (bullet_bridge/contact/rope_rope_contact.h) in the scenes that need it: the knot scene
// while the knot is held tight, the pile scene once the heap has formed (both in ms of wall time per
// simulated second), and how the cost grows with the rope: piles of non-adaptive ropes with
// n = 32, 128, 512 control points (ms per 1/240 s step). Counters split off the rope-rope part
// (narrowphase of the capsule pairs plus the coupled solve) and count the acting self-contacts.

#include <benchmark/benchmark.h>

#include <cmath>

#include "demos/scenes/knot_scene.h"
#include "demos/scenes/pile_scene.h"

namespace {

using rope::bullet::ContactReport;

struct Shares {
  double ropeContact = 0.0;  // s
  long contacts = 0;
  long substeps = 0;
};

void record(rope::demos::PhysicsWorld& physics, Shares& shares) {
  physics.ropes().setSubstepCallback([&shares](const ContactReport& report) {
    shares.ropeContact += report.ropeContactSeconds;
    for (const auto& contact : report.ropeContacts) shares.contacts += contact.active ? 1 : 0;
    ++shares.substeps;
  });
}

void report(benchmark::State& state, const Shares& shares, double stepsPerIteration) {
  const double iterations = static_cast<double>(state.iterations());
  state.counters["rope_contact_ms"] = 1e3 * shares.ropeContact / iterations;  // per iteration
  state.counters["self_contacts"] = static_cast<double>(shares.contacts) / std::max(1L, shares.substeps);
  state.counters["steps"] = stepsPerIteration;
}

// Steps `scene` for `warmUp` simulated seconds untimed, then one simulated second per iteration.
template <typename SceneType>
void simulatedSeconds(benchmark::State& state, SceneType& scene, double warmUp) {
  const int perSecond = static_cast<int>(std::lround(1.0 / scene.timeStep()));
  for (int i = 0; i < static_cast<int>(std::lround(warmUp * perSecond)); ++i) scene.step();
  Shares shares;
  record(scene.physics(), shares);
  for (auto _ : state) {
    for (int i = 0; i < perSecond; ++i) scene.step();
  }
  report(state, shares, perSecond);
  state.counters["control_points"] = scene.rope().rod().controlPointCount();
}

// The knot held tight by the grippers (after 3 s of pulling), one simulated second per iteration.
void BM_KnotHeldTight(benchmark::State& state) {
  rope::demos::KnotScene scene(rope::demos::KnotSceneSettings{});
  simulatedSeconds(state, scene, 3.0);
}
BENCHMARK(BM_KnotHeldTight)->Unit(benchmark::kMillisecond)->Iterations(3);

// The whole tightening: from the loose knot until it is tight (3 simulated seconds), per second.
void BM_KnotTightening(benchmark::State& state) {
  Shares shares;
  int perSecond = 0;
  for (auto _ : state) {
    state.PauseTiming();
    rope::demos::KnotScene scene(rope::demos::KnotSceneSettings{});
    record(scene.physics(), shares);
    perSecond = static_cast<int>(std::lround(1.0 / scene.timeStep()));
    state.ResumeTiming();
    for (int i = 0; i < 3 * perSecond; ++i) scene.step();
  }
  report(state, shares, 3 * perSecond);
  state.counters["ms_per_simulated_s"] =
      benchmark::Counter(3.0 * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_KnotTightening)->Unit(benchmark::kMillisecond)->Iterations(2);

// The 2 m pile once it has landed (after 1 s), one simulated second per iteration.
void BM_PileResting(benchmark::State& state) {
  rope::demos::PileScene scene(rope::demos::PileSceneSettings{});
  simulatedSeconds(state, scene, 1.0);
}
BENCHMARK(BM_PileResting)->Unit(benchmark::kMillisecond)->Iterations(3);

// Piles of n control points (non-adaptive, one per 3 cm of rope), per step once the heap has formed.
void BM_PileScaling(benchmark::State& state) {
  rope::demos::PileSceneSettings settings;
  const int n = static_cast<int>(state.range(0));
  settings.ropeLength = 0.03 * (n - 1);
  settings.rod.adaptive = false;
  settings.rod.maxControlPoints = n + 8;
  rope::demos::PileScene scene(settings);
  const int landing = static_cast<int>(std::lround((0.6 + 0.004 * n) / scene.timeStep()));
  for (int i = 0; i < landing; ++i) scene.step();
  Shares shares;
  record(scene.physics(), shares);
  constexpr int kSteps = 24;
  for (auto _ : state) {
    for (int i = 0; i < kSteps; ++i) scene.step();
  }
  report(state, shares, kSteps);
  state.counters["control_points"] = scene.rope().rod().controlPointCount();
  state.counters["ms_per_step"] = benchmark::Counter(kSteps * static_cast<double>(state.iterations()),
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_PileScaling)->Arg(32)->Arg(128)->Arg(512)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
