// SPDX-License-Identifier: MIT
#pragma once
// "drape" / "thinbar": a rope falls onto a static obstacle in a Bullet world and comes to rest on it —
// a wide box (drape) or a 2 mm square bar it must hang over without tunnelling (thinbar). Both sit
// above a ground plane y = 0.

#include <memory>

#include "bullet_bridge/rope_object.h"
#include "demos/scenes/world_scene.h"

namespace rope::demos {

struct DrapeSceneSettings {
  enum class Obstacle { kBox, kThinBar };
  Obstacle obstacle = Obstacle::kBox;
  double ropeLength = 1.0;        // m, > 0; the rope lies along x, centred over the obstacle
  double dropHeight = 0.2;        // m, >= 0: gap between the rope's underside and the obstacle's top
  double obstacleTop = 0.2;       // m, > 0: height of the obstacle's top face
  double barThickness = 0.002;    // m, > 0: edge of the thin bar's square cross-section
  double timeStep = 1.0 / 240.0;  // s, > 0
  RodSettings rod = defaultRod();
  bullet::BulletRopeSettings bridge;

  static RodSettings defaultRod();  // 1 cm nylon-like rope, lightly damped
  static DrapeSceneSettings thinBar();  // the bar at 1 m, the rope dropped from 1 m above it
};

class DrapeScene : public WorldScene {
 public:
  // Throws InvalidArgument naming the field for bad settings.
  explicit DrapeScene(const DrapeSceneSettings& settings);

  StepMeasurements step() override;
  StepMeasurements measure() const override;
  void draw(render::Scene& scene) const override;
  std::optional<render::Camera> camera() const override;

  const bullet::RopeObject& rope() const { return *rope_; }
  const btRigidBody& obstacle() const { return *obstacle_; }
  // Lowest and highest rope point over a dense sample of the curve, m.
  double lowestPoint() const;
  double highestPoint() const;

 private:
  DrapeSceneSettings settings_;
  btRigidBody* obstacle_ = nullptr;
  std::unique_ptr<bullet::RopeObject> rope_;
};

}  // namespace rope::demos
