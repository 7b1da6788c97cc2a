// SPDX-License-Identifier: MIT
#include "demos/compare/compare.h"

#include <exception>
#include <sstream>

#include "demos/compare/runners.h"
#include "rope/common/error.h"

namespace rope::compare {

std::string Setting::label() const {
  std::ostringstream text;
  text << resolution;
  if (iterations != 1) text << " it" << iterations;
  if (substeps != 1) text << " sub" << substeps;
  if (stiffness != 1.0) text << " kLST" << stiffness;
  if (stretch) text << " stretch";
  return text.str();
}

const char* engineName(Engine engine) {
  switch (engine) {
    case Engine::kSplineRope: return "splinerope";
    case Engine::kSoftBody: return "bullet_softbody";
    case Engine::kMuJoCo: return "mujoco_chain";
  }
  return "?";
}

const char* sceneName(Scene scene) {
  switch (scene) {
    case Scene::kCatenary: return "catenary";
    case Scene::kHeavyLoad: return "heavy_load";
    case Scene::kThinBar: return "thin_bar";
    case Scene::kDrape: return "drape";
    case Scene::kScaling: return "scaling";
  }
  return "?";
}

Trial run(Engine engine, Scene scene, const Setting& setting, const Limits& limits) {
  try {
    switch (engine) {
      case Engine::kSplineRope: return splinerope::run(scene, setting, limits);
      case Engine::kSoftBody: return softbody::run(scene, setting, limits);
      case Engine::kMuJoCo: return mujoco::run(scene, setting, limits);
    }
  } catch (const InvalidArgument&) {
    throw;
  } catch (const std::exception& error) {
    // An engine that cannot even build the scene (e.g. MuJoCo out of memory) is a result, not a crash.
    Trial trial;
    trial.status = std::string("could not run: ") + error.what();
    return trial;
  }
  return Trial{};
}

}  // namespace rope::compare
