// SPDX-License-Identifier: MIT
#pragma once
// "hang": the catenary. A rope lies straight between two pins; the pins are drawn together to the
// final span over closeTime, and the rope sags and settles into a catenary whose sag the analytic
// inextensible catenary predicts (L = 2a sinh(D/2a), sag = a (cosh(D/2a) - 1)).

#include "demos/scenes/demo_scene.h"
#include "rope/rod/rod.h"

namespace rope::demos {

struct HangSceneSettings {
  double ropeLength = 1.25;      // m, > span (slack ratio 1.25 by default)
  double span = 1.0;             // m, final distance between the pins
  double pinHeight = 1.2;        // m, height of both pins above the ground (y = 0)
  double closeTime = 1.0;        // s, time over which the pins move from ropeLength to span apart
  double timeStep = 1.0 / 240.0; // s
  RodSettings rod = defaultRod();

  // A 1 cm nylon-like rope, lightly damped so it settles within a few seconds.
  static RodSettings defaultRod();
};

class HangScene : public DemoScene {
 public:
  // Throws InvalidArgument naming the field for a span not in (0, ropeLength) or bad rod settings.
  explicit HangScene(const HangSceneSettings& settings);

  double timeStep() const override { return settings_.timeStep; }
  StepMeasurements step() override;
  StepMeasurements measure() const override;
  void draw(render::Scene& scene) const override;
  void appendState(std::vector<double>& state) const override;
  std::optional<render::Camera> camera() const override;

  const Rod& rod() const { return rod_; }
  double time() const { return time_; }
  // Pin height minus the lowest point of the curve (sampled densely), m.
  double sag() const;
  // Sag of the inextensible catenary of the same length over the final span, m.
  double analyticSag() const;

 private:
  double pinDistance(double time) const;

  HangSceneSettings settings_;
  Rod rod_;
  int leftPin_ = 0;
  int rightPin_ = 0;
  double time_ = 0.0;
};

}  // namespace rope::demos
