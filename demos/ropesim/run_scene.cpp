// SPDX-License-Identifier: MIT
#include "demos/ropesim/run_scene.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "demos/ropesim/progress.h"
#include "demos/scene_file/built_in_scene_files.h"
#include "demos/scene_file/file_scene.h"
#include "demos/scene_file/junit_report.h"
#include "demos/scene_file/scene_file_reader.h"
#include "render/png_writer.h"
#include "render/renderer.h"
#include "render/video_writer.h"

namespace rope::demos {

RunStatistics runScene(const RopesimOptions& options, std::vector<CheckResult>* checks) {
  const auto wallBegin = std::chrono::steady_clock::now();
  std::unique_ptr<DemoScene> scene;
  FileScene* fileScene = nullptr;
  double defaultSeconds = 0.0;
  std::optional<std::string> file = options.sceneFile;
  if (!file) file = builtInSceneFile(options.scene);
  if (file) {
    std::vector<SceneOverride> overrides;
    for (const std::string& text : options.overrides) overrides.push_back(parseSceneOverride(text));
    auto built = std::make_unique<FileScene>(readSceneFile(*file, overrides), options.checks);
    fileScene = built.get();
    defaultSeconds = built->description().duration;
    scene = std::move(built);
  } else {
    const SceneEntry* entry = findScene(options.scene);
    if (entry == nullptr) throw std::runtime_error("unknown scene '" + options.scene + "'");
    scene = entry->create();
    defaultSeconds = entry->defaultSeconds;
  }
  const double seconds = options.seconds.value_or(defaultSeconds);
  const double h = scene->timeStep();
  // Frame k shows the state at t = k / fps; the video has exactly seconds * fps frames.
  const long frameCount = std::max(1L, std::lround(seconds * options.framesPerSecond));

  std::unique_ptr<render::Renderer> renderer;
  std::unique_ptr<render::VideoWriter> video;
  render::Camera camera;
  if (options.render) {
    render::RenderSettings settings;
    settings.width = options.width;
    settings.height = options.height;
    renderer = std::make_unique<render::Renderer>(settings);
    if (options.framesDirectory) std::filesystem::create_directories(*options.framesDirectory);
    if (options.video) {
      render::VideoSettings videoSettings;
      videoSettings.width = options.width;
      videoSettings.height = options.height;
      videoSettings.framesPerSecond = options.framesPerSecond;
      video = std::make_unique<render::VideoWriter>(*options.video, videoSettings);
    }
  }

  RunStatistics statistics(options.scene);
  StepMeasurements latest = scene->measure();
  render::Scene drawList;
  render::Image image;
  double time = 0.0;
  long steps = 0;
  double renderSeconds = 0.0;
  Progress progress(frameCount, "ropesim " + options.scene, options.quiet);
  using Clock = std::chrono::steady_clock;
  for (long frame = 0; frame < frameCount; ++frame) {
    const double frameTime = static_cast<double>(frame) / options.framesPerSecond;
    // Steps are counted, not accumulated, so the step count does not drift with rounding.
    while (static_cast<double>(steps) * h < frameTime - 0.5 * h) {
      const auto begin = Clock::now();
      latest = scene->step();
      const double micros = std::chrono::duration<double, std::micro>(Clock::now() - begin).count();
      ++steps;
      time = static_cast<double>(steps) * h;
      statistics.addStep(latest, micros, time);
    }
    statistics.addFrame(time, latest);
    if (renderer) {
      const auto begin = Clock::now();
      drawList.clear();
      scene->draw(drawList);
      // A scene's own camera is asked every frame (it may follow the action); without one, the first
      // frame is framed automatically and the camera stays there.
      if (const std::optional<render::Camera> own = scene->camera()) {
        camera = *own;
      } else if (frame == 0) {
        camera = renderer->frameScene(drawList);
      }
      renderer->render(drawList, camera, image);
      renderSeconds += std::chrono::duration<double>(Clock::now() - begin).count();
      if (video) video->addFrame(image);
      if (options.framesDirectory) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%05ld.png", frame);
        render::writePng((std::filesystem::path(*options.framesDirectory) / name).string(), image);
      }
    }
    progress.update(frame + 1);
  }
  // The last frame shows t = (frameCount - 1) / fps; simulate to the full duration.
  while (static_cast<double>(steps) * h < seconds - 0.5 * h) {
    const auto begin = Clock::now();
    latest = scene->step();
    const double micros = std::chrono::duration<double, std::micro>(Clock::now() - begin).count();
    ++steps;
    statistics.addStep(latest, micros, static_cast<double>(steps) * h);
  }
  progress.finish();
  if (video) video->close();
  if (renderer && renderSeconds > 0.0) statistics.setRenderFramesPerSecond(frameCount / renderSeconds);

  if (fileScene != nullptr && options.checks) {
    fileScene->finishChecks();
    const std::vector<CheckResult>& results = fileScene->checks().results();
    if (checks != nullptr) *checks = results;
    if (options.junitFile) {
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallBegin).count();
      writeJunitReport(*options.junitFile, options.scene, results, wall);
    }
  }
  if (options.statsFile) {
    std::ofstream file(*options.statsFile);
    file << statistics.toJson();
    if (!file) throw std::runtime_error("cannot write statistics to '" + *options.statsFile + "'");
  }
  return statistics;
}

}  // namespace rope::demos
