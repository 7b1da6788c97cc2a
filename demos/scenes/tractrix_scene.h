// SPDX-License-Identifier: MIT
#pragma once
// "tractrix": [B]'s follow-the-leader kinematics. Two ropes of the same length follow the same
// figure-eight path with their leading ends, side by side: TRX (an exact polyline of 20 rigid
// segments) and TRX_SD_MRG (a cubic spline control polygon that subdivides where it bends and
// merges where it straightens, with the default length correction that keeps the curve's length).
// The stats record both ropes' length errors.

#include "demos/scenes/demo_scene.h"
#include "rope/tractrix/tractrix_rope.h"

namespace rope::demos {

struct TractrixSceneSettings {
  double ropeLength = 1.5;        // m
  double radius = 0.015;          // m, drawn tube radius (kinematic: no contact)
  double loopRadius = 1.0;        // m, half width of the figure-eight path
  double period = 10.0;           // s, one lap of the path
  double timeStep = 1.0 / 60.0;   // s, one leading-end move per step
  double separation = 2.6;        // m, distance between the two paths' centres (along x)
  int polylineSegments = 20;      // TRX
  int splineSides = 6;            // TRX_SD_MRG's initial control polygon sides ([B] §4)
};

class TractrixScene : public DemoScene {
 public:
  // Throws InvalidArgument naming the field for non-positive lengths, times or counts.
  explicit TractrixScene(const TractrixSceneSettings& settings);

  double timeStep() const override { return settings_.timeStep; }
  StepMeasurements step() override;
  StepMeasurements measure() const override;
  void draw(render::Scene& scene) const override;
  void appendState(std::vector<double>& state) const override;
  std::optional<render::Camera> camera() const override;

  const TractrixRope& polylineRope() const { return polyline_; }
  const TractrixRope& splineRope() const { return spline_; }
  // The leading end's path for a rope whose path is centred at centre, at time t (s).
  Vec3 pathPoint(const Vec3& centre, double t) const;

 private:
  TractrixSceneSettings settings_;
  Vec3 polylineCentre_;
  Vec3 splineCentre_;
  TractrixRope polyline_;
  TractrixRope spline_;
  double time_ = 0.0;
};

}  // namespace rope::demos
