// SPDX-License-Identifier: MIT
#pragma once
// rope_compare: the same physical scenes run with SplineRope, Bullet's btSoftBody rope
// (btSoftBodyHelpers::CreateRope) and a MuJoCo 2.2 rope (<composite type="rope">: a chain of
// capsules, two hinges per link). Every engine gets the scene's length, mass, radius, gravity and
// time step; stiffness and damping are matched as far as each model allows (see each runner).
// SI units throughout; y is up in all three engines.

#include <algorithm>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace rope::compare {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One discretisation / solver choice of one engine. Which fields matter depends on the engine:
// SplineRope: resolution = initial control points; soft body: resolution = nodes, iterations =
// piterations, stiffness = kLST; MuJoCo: resolution = links, substeps = mj_step calls per scene
// step (timestep / substeps), stretch = slide joints along each link (EA / link length).
struct Setting {
  int resolution = 16;   // control points / nodes / links, >= 2
  int iterations = 1;    // solver iterations (soft body piterations), >= 1
  int substeps = 1;      // engine steps per scene time step, >= 1
  double stiffness = 1.0;  // soft body link stiffness kLST in (0, 1]
  bool stretch = false;  // MuJoCo only: axial slide joints so the chain can stretch
  std::string label() const;
};

// Wall-clock limits of one trial: a trial that would exceed wallBudget seconds stops early and is
// reported as too slow (its cost is then a lower bound), so the whole program stays bounded.
struct Limits {
  double wallBudget = 20.0;  // s, > 0
  double seconds = 0.0;      // simulated s; 0: the scene's default
  double loadMass = 0.0;     // kg, heavy-load scene only; 0: the scene's 10 kg
};

// What one run of one scene with one setting measured.
struct Trial {
  std::string status = "ok";    // "ok", or how it failed: "exploded", "too slow", "fell through", ...
  double simulatedSeconds = 0.0;  // s actually simulated
  double wallSeconds = 0.0;       // s of wall time spent in the engine's step calls only
  int steps = 0;                  // scene steps taken
  int dofs = 0;                   // degrees of freedom at the end (3 per control point / node; nv for MuJoCo)
  std::map<std::string, double> metrics;  // scene figures (sag_error, strain_error, ...)
  std::vector<double> stepSeconds;        // wall time of each timed step

  // Median wall time of one step, us: robust against the odd step where the shared machine
  // preempted the process (the scaling figure).
  double medianStepMicroseconds() const {
    if (stepSeconds.empty()) return kNaN;
    std::vector<double> sorted = stepSeconds;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    return 1e6 * sorted[sorted.size() / 2];
  }

  bool ok() const { return status == "ok"; }
  // Wall seconds per simulated second (NaN before any step).
  double costPerSecond() const { return simulatedSeconds > 0 ? wallSeconds / simulatedSeconds : kNaN; }
  double stepMicroseconds() const { return steps > 0 ? 1e6 * wallSeconds / steps : kNaN; }
};

enum class Engine { kSplineRope, kSoftBody, kMuJoCo };
const char* engineName(Engine engine);

enum class Scene { kCatenary, kHeavyLoad, kThinBar, kDrape, kScaling };
const char* sceneName(Scene scene);

// Runs one scene with one engine and setting. Never throws for a simulation failure (it is the
// trial's status); throws InvalidArgument naming the field for a bad setting.
Trial run(Engine engine, Scene scene, const Setting& setting, const Limits& limits);

}  // namespace rope::compare
