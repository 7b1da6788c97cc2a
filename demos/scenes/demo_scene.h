// SPDX-License-Identifier: MIT
#pragma once
// A demo scene: a small simulation that `ropesim` runs, renders and measures. Tests and benchmarks
// build the very same scenes (one set of scene builders, as Box2D keeps its samples), so a demo
// scene is also a tested scene.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "render/camera.h"
#include "render/scene.h"

namespace rope::demos {

// What one step did, summed or maximised over the scene's ropes.
struct StepMeasurements {
  int controlPoints = 0;  // after the step's adaptivity
  int insertions = 0;     // knots inserted in this step
  int removals = 0;       // knots removed in this step
  double maxStrain = 0.0; // largest |C'|/l0' - 1, dimensionless
  // Measured only by scenes with rigid contact / self-contact; nullopt where not measured.
  std::optional<double> maxPenetration;  // m, rope into rigid bodies
  std::optional<double> maxSelfOverlap;  // m, rope into itself
  // Scene-specific quantities recorded per frame under their name (e.g. a length error).
  std::vector<std::pair<std::string, double>> series;
};

class DemoScene {
 public:
  virtual ~DemoScene() = default;
  // Fixed step of the simulation, s.
  virtual double timeStep() const = 0;
  // Advances one timeStep(). Throws std::runtime_error naming the failure if the simulation fails.
  virtual StepMeasurements step() = 0;
  // The measurements of the current state without stepping (insertions and removals zero): what
  // the first frame, before any step, records.
  virtual StepMeasurements measure() const = 0;
  // Adds the current geometry to a draw list (no GL involved).
  virtual void draw(render::Scene& scene) const = 0;
  // Appends the scene's full dynamic state (rods, tractrix ropes, Bullet bodies: scene_state.h) to
  // `state`, for the golden determinism hash (tests/reliability/golden_hash_test.cpp).
  virtual void appendState(std::vector<double>& state) const = 0;
  // The camera for the current state (asked before every frame, so it may follow the action), or
  // nullopt to frame the first frame automatically and keep that camera.
  virtual std::optional<render::Camera> camera() const { return std::nullopt; }
};

struct SceneEntry {
  std::string name;
  std::string description;
  double defaultSeconds = 10.0;  // simulated seconds ropesim runs by default
  std::function<std::unique_ptr<DemoScene>()> create;
};

// Every scene ropesim knows, in the order its help lists them.
const std::vector<SceneEntry>& sceneCatalogue();
// nullptr if there is no scene of that name.
const SceneEntry* findScene(const std::string& name);

}  // namespace rope::demos
