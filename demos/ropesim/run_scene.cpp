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
#include "render/png_writer.h"
#include "render/renderer.h"
#include "render/video_writer.h"

namespace rope::demos {

RunStatistics runScene(const RopesimOptions& options) {
  const SceneEntry* entry = findScene(options.scene);
  if (entry == nullptr) throw std::runtime_error("unknown scene '" + options.scene + "'");
  std::unique_ptr<DemoScene> scene = entry->create();
  const double seconds = options.seconds.value_or(entry->defaultSeconds);
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

  if (options.statsFile) {
    std::ofstream file(*options.statsFile);
    file << statistics.toJson();
    if (!file) throw std::runtime_error("cannot write statistics to '" + *options.statsFile + "'");
  }
  return statistics;
}

}  // namespace rope::demos
