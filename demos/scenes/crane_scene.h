// SPDX-License-Identifier: MIT
#pragma once
// "crane": a heavy box (10 kg) hangs from a light rope (1 m, 0.01 kg/m): the rope's top is a moving
// world target (a pin), its bottom is attached to the box's top face (two-way body attachment, mass
// ratio 1000:1). The box settles where the rope's stretch carries its weight (strain W / EA); after
// liftStart the top is raised by liftHeight over liftDuration and the box follows.

#include <memory>

#include "bullet_bridge/rope_object.h"
#include "demos/scenes/hanging_box.h"
#include "demos/scenes/world_scene.h"

namespace rope::demos {

struct CraneSceneSettings {
  double ropeLength = 1.0;        // m, > 0
  double topHeight = 2.0;         // m: the rope's top pin (the ground is y = 0)
  double boxMass = 10.0;          // kg, > 0
  double boxHalfExtent = 0.1;     // m, > 0 (a cube)
  double liftStart = 3.0;         // s, >= 0 (a large value: never lift)
  double liftHeight = 0.3;        // m, finite
  double liftDuration = 2.0;      // s, > 0
  double timeStep = 1.0 / 240.0;  // s, > 0
  RodSettings rod = defaultRod();
  bullet::BulletRopeSettings bridge;
  bullet::AttachmentSettings attachment;

  // 0.01 kg/m, radius 4 mm, E = 5e8 Pa (EA = 25.1 kN), stiffness damping so the bounce decays.
  static RodSettings defaultRod();
};

class CraneScene : public WorldScene {
 public:
  explicit CraneScene(const CraneSceneSettings& settings);

  StepMeasurements step() override;
  StepMeasurements measure() const override;
  void draw(render::Scene& scene) const override;
  std::optional<render::Camera> camera() const override;

  const bullet::RopeObject& rope() const { return *rig_.rope; }
  const btRigidBody& box() const { return *rig_.box; }
  // Height of the top pin at time t, m.
  double topHeight(double t) const;
  // Distance between the rope's end and the box's attachment point, m.
  double attachmentGap() const;
  // Strain of a rope carrying the box's weight alone: m g / (E A).
  double expectedStrain() const;

 private:
  CraneSceneSettings settings_;
  HangingBox rig_;
  long steps_ = 0;
};

}  // namespace rope::demos
