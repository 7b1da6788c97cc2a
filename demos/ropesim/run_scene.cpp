// SPDX-License-Identifier: MIT
#include "demos/ropesim/run_scene.h"

#include <cctype>
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
#include "render/primitive_mesh.h"
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

  // --snapshot-on-failure: a picture of the moment a check first fails, what failed marked by a red
  // sphere drawn over everything (an overlay), from the scene's camera (or the first frame's).
  std::unique_ptr<render::Renderer> snapshotRenderer;
  std::optional<render::Camera> frame0Camera;  // the automatic framing of the first frame, if rendered
  auto snapshotFailures = [&]() {
    if (fileScene == nullptr || !options.snapshotDirectory || fileScene->checks().newFailures().empty()) return;
    render::Renderer* snapshots = renderer.get();
    if (snapshots == nullptr) {
      if (!snapshotRenderer) {
        render::RenderSettings settings;
        settings.width = options.width;
        settings.height = options.height;
        snapshotRenderer = std::make_unique<render::Renderer>(settings);
      }
      snapshots = snapshotRenderer.get();
    }
    std::filesystem::create_directories(*options.snapshotDirectory);
    for (const std::size_t index : fileScene->checks().newFailures()) {
      const CheckResult& check = fileScene->checks().results()[index];
      render::Scene snapshotScene;
      scene->draw(snapshotScene);
      const render::Camera view = scene->camera().value_or(frame0Camera ? *frame0Camera : snapshots->frameScene(snapshotScene));
      // 1.5 % of the viewing distance: visible at any zoom, small enough to point at a contact.
      const double radius = 0.015 * (view.eye - view.target).norm();
      Eigen::Isometry3d place = Eigen::Isometry3d::Identity();
      place.translate(check.marker);
      snapshotScene.add(std::make_shared<render::Mesh>(render::makeSphere(radius, 24)), place,
                        render::Rgb(1.0f, 0.1f, 0.1f), render::Material::Overlay);
      std::string name;
      for (const char c : check.name) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
      char prefix[16];
      std::snprintf(prefix, sizeof prefix, "%02zu_", index);
      const std::string file = (std::filesystem::path(*options.snapshotDirectory) / (prefix + name + ".png")).string();
      render::writePng(file, snapshots->render(snapshotScene, view));
      fileScene->checks().setSnapshot(index, file);
    }
  };

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
      snapshotFailures();
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
        frame0Camera = camera;
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
    snapshotFailures();
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
