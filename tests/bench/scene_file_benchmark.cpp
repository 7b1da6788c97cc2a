// SPDX-License-Identifier: MIT
// Scene files (issue 18, demos/scene_file):
//   * reading and validating a file of 10 ropes and 100 bodies (target: under 50 ms), and reading it
//     and building its world;
//   * the cost of the checks per step: the same scene stepped with its checks evaluated and without
//     (FileScene's checksEnabled), on the pile (demos/scenes/pile.json plus knot length and tension
//     checks) once it has landed (after 1 s), and on a knot pulled tight by two moving pins (the knot
//     scene's overhand polyline, cord and contact laws: demos/scenes/knot_scene.h) after 2 s
//     (target: under 5 %).
//   The checks alone (BM_*Checks: one evaluation of all of a scene's checks) against the step time
//   is the same ratio without the noise of comparing two timed runs on a shared machine.
// One iteration is one read, one step or one evaluation of the checks; run with --benchmark_repetitions=5 and compare the medians.
#include <benchmark/benchmark.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "demos/scene_file/built_in_scene_files.h"
#include "demos/scene_file/file_scene.h"
#include "demos/scene_file/scene_file_reader.h"
#include "demos/scenes/knot_scene.h"

#include <nlohmann/json.hpp>

namespace {

using namespace rope::demos;

// 100 boxes in a 10 x 10 grid, 10 ropes over them each pinned at one end and attached to a box at
// the other, with every kind of check.
std::string largeScene() {
  std::ostringstream text;
  text << R"({"description": "10 ropes, 100 bodies", "duration": 1.0, "bodies": [)";
  for (int i = 0; i < 100; ++i) {
    text << (i ? "," : "") << R"({"name": "box)" << i << R"(", "shape": "box", "motion": ")"
         << (i % 2 ? "dynamic\", \"mass\": 1.0" : "static\"") << R"(, "halfExtents": [0.04, 0.04, 0.04], "position": [)"
         << 0.1 * (i % 10) << ", 0.04, " << 0.1 * (i / 10) << R"(], "friction": 0.6})";
  }
  text << R"(], "ropes": [)";
  for (int r = 0; r < 10; ++r) {
    text << (r ? "," : "") << R"({"name": "rope)" << r << R"(", "settings": {"restLength": 1.2, "radius": 0.004,
      "youngsModulus": 2e8, "massDamping": 0.2, "friction": 0.8, "selfContact": true},
      "shape": {"type": "segment", "from": [0, 0.3, )" << 0.1 * r << R"(], "to": [0.9, 0.3, )" << 0.1 * r << R"(]},
      "pins": [{"name": "top", "s": "begin"}],
      "attachments": [{"name": "load", "s": "end", "body": "box)" << (10 * r + 1) << R"(", "localPoint": [0, 0.04, 0]}]})";
  }
  text << R"(], "checks": [)";
  for (int r = 0; r < 10; ++r) {
    text << (r ? "," : "") << R"({"name": "no sinking )" << r << R"(", "type": "penetration", "rope": "rope)" << r
         << R"(", "max": 0.002}, {"name": "load )" << r << R"(", "type": "tension", "rope": "rope)" << r
         << R"(", "attachment": "load", "min": 0, "max": 50})";
  }
  text << R"(, {"name": "healthy", "type": "health"}]})";
  return text.str();
}

void BM_ReadLargeSceneFile(benchmark::State& state) {
  const std::string text = largeScene();
  std::size_t bodies = 0;
  for (auto _ : state) {
    const SceneDescription scene = readSceneText(text);
    bodies += scene.bodies.size();
    benchmark::DoNotOptimize(bodies);
  }
  state.counters["bytes"] = static_cast<double>(text.size());
}
BENCHMARK(BM_ReadLargeSceneFile)->Unit(benchmark::kMillisecond);

void BM_ReadAndBuildLargeSceneFile(benchmark::State& state) {
  const std::string text = largeScene();
  for (auto _ : state) {
    FileScene scene(readSceneText(text));
    benchmark::DoNotOptimize(scene.time());
  }
}
BENCHMARK(BM_ReadAndBuildLargeSceneFile)->Unit(benchmark::kMillisecond);

nlohmann::json readJson(const std::string& file) {
  std::ifstream stream(file);
  return nlohmann::json::parse(stream);
}

// demos/scenes/pile.json with three more checks.
SceneDescription pileWithChecks() {
  nlohmann::json pile = readJson(*builtInSceneFile("pile"));
  for (const char* check : {R"({"name": "knot", "type": "knotLength", "rope": "rope", "max": 2.5})",
                            R"({"name": "middle", "type": "tension", "rope": "rope", "s": 1.0, "max": 100})",
                            R"({"name": "lands", "type": "contact", "rope": "rope", "body": "ground", "mode": "stays", "from": 1.0})"}) {
    pile["checks"].push_back(nlohmann::json::parse(check));
  }
  return readSceneJson(pile);
}

// The knot scene's overhand knot (its polyline, cord and contact laws), its ends held by pins that
// draw apart by 5 cm each between 0.5 s and 1.5 s instead of the scene's force-controlled grippers.
SceneDescription knotWithChecks() {
  const KnotSceneSettings knot;
  nlohmann::json scene = nlohmann::json::parse(R"({
    "bodies": [{"name": "ground", "shape": "plane", "friction": 0.5477225575051661}],
    "ropes": [{"name": "rope", "shape": {"type": "polyline", "restShape": "asGiven"},
               "settings": {"radius": 0.005, "youngsModulus": 1e8, "bendingStiffness": 1e-4, "massDamping": 0.5,
                            "stiffnessDamping": 1e-3, "maxControlPoints": 160, "friction": 0.5477225575051661}}],
    "checks": [{"name": "knot", "type": "knotLength", "rope": "rope", "max": 1.0},
               {"name": "ground", "type": "contact", "rope": "rope", "body": "ground", "mode": "never"},
               {"name": "end tension", "type": "tension", "rope": "rope", "s": "end", "max": 100},
               {"name": "middle", "type": "position", "rope": "rope", "s": 0.5, "box": {"min": [-1, 0, -1], "max": [1, 1, 1]}},
               {"name": "healthy", "type": "health"}]})");
  const rope::PointList points = overhandKnotPolyline(knot);
  nlohmann::json& rope = scene["ropes"][0];
  for (const rope::Vec3& p : points) rope["shape"]["points"].push_back({p.x(), p.y(), p.z()});
  for (const bool begin : {true, false}) {
    const rope::Vec3 end = begin ? points.front() : points.back();
    const rope::Vec3 away = (end - (begin ? points.back() : points.front())).normalized();
    const rope::Vec3 pulled = end + 0.05 * away;
    rope["pins"].push_back({{"s", begin ? "begin" : "end"},
                            {"keyframes", {{{"time", 0.5}, {"position", {end.x(), end.y(), end.z()}}},
                                           {{"time", 1.5}, {"position", {pulled.x(), pulled.y(), pulled.z()}}}}}});
  }
  return readSceneJson(scene);
}

void stepScene(benchmark::State& state, const SceneDescription& description, double warmUp) {
  FileScene scene(description, state.range(0) != 0);
  while (scene.time() < warmUp) scene.step();
  for (auto _ : state) scene.step();
  state.counters["checks"] = state.range(0) != 0 ? static_cast<double>(description.checks.size()) : 0.0;
}

// The checks alone: one evaluation of all of them on the scene's state after warmUp (what each step
// adds), to set against the step time above without the noise of two timed runs.
void observeChecks(benchmark::State& state, const SceneDescription& description, double warmUp) {
  FileScene scene(description, false);
  while (scene.time() < warmUp) scene.step();
  SceneChecks checks(description.checks);
  for (auto _ : state) checks.observe(scene);
  state.counters["checks"] = static_cast<double>(description.checks.size());
}

void BM_PileChecks(benchmark::State& state) { observeChecks(state, pileWithChecks(), 1.0); }
BENCHMARK(BM_PileChecks)->Unit(benchmark::kMicrosecond);

void BM_KnotChecks(benchmark::State& state) { observeChecks(state, knotWithChecks(), 2.0); }
BENCHMARK(BM_KnotChecks)->Unit(benchmark::kMicrosecond);

void BM_PileFileStep(benchmark::State& state) { stepScene(state, pileWithChecks(), 1.0); }
BENCHMARK(BM_PileFileStep)->ArgName("checks")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_KnotFileStep(benchmark::State& state) { stepScene(state, knotWithChecks(), 2.0); }
BENCHMARK(BM_KnotFileStep)->ArgName("checks")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
