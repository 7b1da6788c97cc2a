// SPDX-License-Identifier: MIT
#pragma once
// The checks of a scene file (docs/scene-files.md, "checks"), evaluated after every step over their
// time window. Each reduces a step to one measured value and a margin that is >= 0 while the check
// holds; a check keeps the value with the smallest margin (its worst) and the first time it
// occurred. A check whose window holds no step fails ("not evaluated"), so a typo in a time cannot
// turn a check into one that always passes.

#include <limits>
#include <string>
#include <vector>

#include "demos/scene_file/scene_description.h"
#include "rope/common/types.h"

namespace rope::demos {

class FileScene;

struct CheckResult {
  std::string name;
  std::string type;         // "penetration", "tension", ...
  std::string unit;         // of the value and the bound ("m", "N", "contacts", "warnings")
  std::string bound;        // "<= 0.002", ">= 1", "in [5, 20]"
  long samples = 0;         // steps evaluated
  bool passed = true;
  double worst = std::numeric_limits<double>::quiet_NaN();  // measured value at the worst step
  double worstMargin = std::numeric_limits<double>::infinity();
  double worstTime = std::numeric_limits<double>::quiet_NaN();  // s, first time the worst occurred
  double latest = std::numeric_limits<double>::quiet_NaN();     // value at the last evaluated step
  std::string message;      // one line for people: what failed, the worst value, when
  double firstFailureTime = std::numeric_limits<double>::quiet_NaN();  // s, first step outside the bound
  Vec3 marker = Vec3::Zero();  // m, world: what failed then (the deepest contact, the rope point, the body)
  std::string snapshot;        // the PNG of that moment (ropesim --snapshot-on-failure), "" if none
};

class SceneChecks {
 public:
  explicit SceneChecks(std::vector<CheckDescription> checks);
  // After a step that ended at scene.time().
  void observe(const FileScene& scene);
  // After the run (which ended at endTime): fails the checks that were never evaluated and writes
  // every message.
  void finish(double endTime);
  const std::vector<CheckResult>& results() const { return results_; }
  bool passed() const;
  // The checks that failed for the first time in the last observe() (indices into results()).
  const std::vector<std::size_t>& newFailures() const { return newFailures_; }
  void setSnapshot(std::size_t i, const std::string& file) { results_.at(i).snapshot = file; }

 private:
  struct State {
    bool started = false;
    double baseline = 0.0;       // slip: the parameter at the window's start
    double previousTotal = 0.0;  // health: the warning count after the previous step
    double accumulated = 0.0;    // health: warnings counted in the window's steps
  };
  // The measured value of check i now, or false if it cannot be measured now (rope not there yet).
  bool measure(std::size_t i, const FileScene& scene, double& value);
  double margin(const CheckDescription& check, double value) const;
  // Where check i fails now, for the picture of the failure (run only on a first failure).
  Vec3 marker(std::size_t i, const FileScene& scene) const;
  std::vector<CheckDescription> checks_;
  std::vector<CheckResult> results_;
  std::vector<State> states_;
  std::vector<std::size_t> newFailures_;
};

}  // namespace rope::demos
