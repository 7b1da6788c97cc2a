// SPDX-License-Identifier: MIT
#pragma once
// "sweep": a kinematic tractrix rope ([B], bullet_bridge/kinematic_rope.h) dragged over the ground
// through a field of light boxes: its leading end follows a circle at constant speed, the rest follows
// the leader (TRX_SD_MRG), and the boxes it sweeps are pushed aside one way (the rope is kinematic).
// A hose or cable dragged by a robot across a cluttered floor.

#include <memory>
#include <vector>

#include "bullet_bridge/kinematic_rope.h"
#include "demos/scenes/world_scene.h"

namespace rope::demos {

struct SweepSceneSettings {
  double ropeLength = 1.5;       // m, > 0: initially straight along -x from the circle's start
  double radius = 0.01;          // m, > 0: the rope's radius
  double circleRadius = 0.5;     // m, > 0: the leading end's path, centred on the origin
  double speed = 0.8;            // m/s, > 0: the leading end's speed along the circle
  int boxesPerSide = 5;          // 1..20: a square field of boxes centred on the circle's rim
  double boxHalfExtent = 0.025;  // m, > 0
  double boxSpacing = 0.15;      // m, > 2 boxHalfExtent
  double boxMass = 0.1;          // kg, > 0
  double timeStep = 1.0 / 240.0;  // s, > 0
};

class SweepScene : public WorldScene {
 public:
  explicit SweepScene(const SweepSceneSettings& settings);
  ~SweepScene() override;

  StepMeasurements step() override;
  StepMeasurements measure() const override;
  void draw(render::Scene& scene) const override;
  void appendState(std::vector<double>& state) const override;
  std::optional<render::Camera> camera() const override;

  const bullet::KinematicRope& rope() const { return *rope_; }
  const std::vector<btRigidBody*>& boxes() const { return boxes_; }
  // Where the leading end is at simulated time t (m).
  btVector3 path(double t) const;
  // Largest distance a box has moved from where it started, m.
  double largestBoxDisplacement() const;

 private:
  SweepSceneSettings settings_;
  std::vector<btRigidBody*> boxes_;
  std::vector<btVector3> starts_;
  std::unique_ptr<bullet::KinematicRope> rope_;
};

}  // namespace rope::demos
