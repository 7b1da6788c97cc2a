// SPDX-License-Identifier: MIT
// Frame time of the offscreen renderer at 1280x720 with shadows and anti-aliasing, read-back
// included, plus the pieces a rope demo pays per frame (tube sweep, video encoding). Frames are
// timed one per repetition so that the reported median is a frame-time median; wall-clock time,
// because llvmpipe renders on its own threads.

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "render/renderer.h"
#include "render/rope_drawing.h"
#include "render/tube_mesh.h"
#include "render/video_writer.h"
#include "render/world_extraction.h"
#include "demos/scenes/knot_scene.h"
#include "test_scene.h"

namespace {

using namespace rope::render;

// CPU time of the whole process (main thread and llvmpipe's workers) in milliseconds: the work a
// frame takes, which, unlike the wall-clock time, does not grow when other processes share the cores.
double processCpuMilliseconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return (usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) * 1e3 + (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-3;
}

// The reference scene's rope swinging: new control points every frame, like a simulation.
rope::PointList animatedPoints(int frame) {
  rope::PointList points = test::ropePoints();
  for (std::size_t i = 1; i + 1 < points.size(); ++i) {
    points[i].z() += 0.15 * std::sin(0.2 * frame + 0.7 * static_cast<double>(i));
  }
  return points;
}

void renderFrames(benchmark::State& state, RenderSettings settings, bool animated) {
  test::TestWorld world;
  ShapeMeshCache cache;
  Renderer renderer(settings);
  Scene scene = test::buildScene(world, cache);
  const Camera camera = renderer.frameScene(scene);
  Image image;
  renderer.render(scene, camera, image);  // warm-up: shader compilation, first uploads
  int frame = 0;
  const double cpuBefore = processCpuMilliseconds();
  for (auto _ : state) {
    if (animated) {
      scene.clear();
      extractWorld(world.world, cache, scene);
      RopeStyle style;
      style.tube.radius = test::kRopeRadius;
      addRope(scene, test::ropeKnots(), animatedPoints(frame++), style);
    }
    renderer.render(scene, camera, image);
    benchmark::DoNotOptimize(image.pixels.data());
  }
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["process_cpu_ms"] = (processCpuMilliseconds() - cpuBefore) / static_cast<double>(state.iterations());
}

// A frame of the main job: the knot scene (tight knot, grippers, ground) drawn from its own camera,
// draw-list extraction included, as ropesim renders it (the simulation is stepped outside the timing).
void BM_Render720pKnotScene(benchmark::State& state) {
  rope::demos::KnotScene knot(rope::demos::KnotSceneSettings{});
  for (int i = 0; i < 720; ++i) knot.step();
  Renderer renderer(RenderSettings{});
  Scene scene;
  Image image;
  knot.draw(scene);
  renderer.render(scene, *knot.camera(), image);  // warm-up
  const double cpuBefore = processCpuMilliseconds();
  for (auto _ : state) {
    state.PauseTiming();
    for (int i = 0; i < 8; ++i) knot.step();  // 1/30 s of simulation between frames
    state.ResumeTiming();
    scene.clear();
    knot.draw(scene);
    renderer.render(scene, *knot.camera(), image);
    benchmark::DoNotOptimize(image.pixels.data());
  }
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["process_cpu_ms"] = (processCpuMilliseconds() - cpuBefore) / static_cast<double>(state.iterations());
}

void BM_Render720pShadowsPostAA(benchmark::State& state) { renderFrames(state, RenderSettings{}, false); }
void BM_Render720pShadowsPostAAMovingRope(benchmark::State& state) { renderFrames(state, RenderSettings{}, true); }
void BM_Render720pShadowsMsaa4(benchmark::State& state) {
  RenderSettings settings;
  settings.samples = 4;
  settings.postAntiAliasing = false;
  renderFrames(state, settings, false);
}
void BM_Render720pNoShadowsNoAA(benchmark::State& state) {
  RenderSettings settings;
  settings.shadows = false;
  settings.postAntiAliasing = false;
  renderFrames(state, settings, false);
}

void BM_TubeMesh(benchmark::State& state) {
  const rope::KnotVector knots = rope::KnotVector::clampedUniform(3, static_cast<int>(state.range(0)));
  rope::PointList points;
  for (int i = 0; i < knots.controlPointCount(); ++i) points.push_back(rope::Vec3(0.05 * i, std::sin(0.3 * i), 0.0));
  for (auto _ : state) benchmark::DoNotOptimize(buildTubeMesh(knots, points).vertices.data());
}

// The default demo video: 10 s at 30 fps, 1280x720, moving rope, rendered and encoded (H.264).
void BM_TenSecondVideo(benchmark::State& state) {
  if (findExecutable("ffmpeg").empty()) {
    state.SkipWithError("ffmpeg not installed");
    return;
  }
  test::TestWorld world;
  ShapeMeshCache cache;
  for (auto _ : state) {
    Renderer renderer;
    VideoSettings video;
    VideoWriter writer("/tmp/splinerope_render_benchmark.mp4", video);
    Scene scene;
    Image image;
    Camera camera;
    for (int frame = 0; frame < 300; ++frame) {
      scene.clear();
      extractWorld(world.world, cache, scene);
      RopeStyle style;
      style.tube.radius = test::kRopeRadius;
      addRope(scene, test::ropeKnots(), animatedPoints(frame), style);
      if (frame == 0) camera = renderer.frameScene(scene);
      renderer.render(scene, camera, image);
      writer.addFrame(image);
    }
    writer.close();
  }
}

}  // namespace

BENCHMARK(BM_Render720pShadowsPostAA)->Iterations(1)->Repetitions(60)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Render720pShadowsPostAAMovingRope)->Iterations(1)->Repetitions(60)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Render720pShadowsMsaa4)->Iterations(1)->Repetitions(30)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Render720pNoShadowsNoAA)->Iterations(1)->Repetitions(30)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Render720pKnotScene)->Iterations(1)->Repetitions(60)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TubeMesh)->Arg(16)->Arg(64)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TenSecondVideo)->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);
