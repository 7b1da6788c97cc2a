// SPDX-License-Identifier: MIT
#pragma once
// What a ropesim run measured, and its --stats JSON (one object; keys documented in README.md).

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "demos/scenes/demo_scene.h"

namespace rope::demos {

class RunStatistics {
 public:
  explicit RunStatistics(std::string scene) : scene_(std::move(scene)) {}

  // After every step: its measurements and its wall time (microseconds).
  void addStep(const StepMeasurements& measurements, double wallMicroseconds, double simulatedTime);
  // At every frame: the simulated time and the latest step's measurements.
  void addFrame(double time, const StepMeasurements& latest);
  void setRenderFramesPerSecond(double fps) { renderFps_ = fps; }

  long steps() const { return steps_; }
  double maxStrain() const { return maxStrain_; }
  int finalControlPoints() const { return finalControlPoints_; }
  // Median and 95th percentile of the step wall times, microseconds (0 before any step).
  double stepTimeMedian() const;
  double stepTimeP95() const;

  std::string toJson() const;

 private:
  std::string scene_;
  double simulatedSeconds_ = 0.0;
  long steps_ = 0;
  std::vector<double> stepMicroseconds_;
  int minControlPoints_ = 0;
  int maxControlPoints_ = 0;
  int finalControlPoints_ = 0;
  long insertions_ = 0;
  long removals_ = 0;
  double maxStrain_ = 0.0;
  std::optional<double> maxPenetration_;
  std::optional<double> maxSelfOverlap_;
  std::optional<double> renderFps_;
  std::vector<double> frameTimes_;
  std::vector<double> frameControlPoints_;
  std::vector<double> frameMaxStrain_;
  std::vector<std::pair<std::string, std::vector<double>>> frameSeries_;
};

// Quantile q in [0, 1] of values by linear interpolation between order statistics (0 when empty).
double quantile(std::vector<double> values, double q);

}  // namespace rope::demos
