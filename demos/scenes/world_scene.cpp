// SPDX-License-Identifier: MIT
#include "demos/scenes/world_scene.h"

#include <utility>

#include "demos/scenes/scene_state.h"

namespace rope::demos {

WorldScene::WorldScene(std::string name, double timeStep, const btVector3& gravity)
    : physics_(gravity), name_(std::move(name)), timeStep_(timeStep) {}

void WorldScene::appendState(std::vector<double>& state) const { appendWorldState(physics_, state); }

StepMeasurements WorldScene::advance(double time) {
  const StepMeasurements counts = stepAndCheck(physics_, timeStep_, name_);
  time_ = time;
  StepMeasurements measurements = measure();
  measurements.insertions = counts.insertions;
  measurements.removals = counts.removals;
  return measurements;
}

}  // namespace rope::demos
