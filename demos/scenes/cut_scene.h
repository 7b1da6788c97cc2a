// SPDX-License-Identifier: MIT
#pragma once
// "cut": cutting a loaded rope in a Bullet world ([A] §5.1). A 2 kg box hangs from a 1 m rope pinned
// at the top and swings as a pendulum; at cutTime the rope is cut (RopeObject::cut) at cutFraction of
// its length. The box falls freely with the lower piece still attached, while the upper piece keeps
// its pin and swings on: two ropes in the world from then on, with their own capsules and contacts.

#include <memory>

#include "bullet_bridge/rope_object.h"
#include "demos/scenes/hanging_box.h"
#include "demos/scenes/world_scene.h"

namespace rope::demos {

struct CutSceneSettings {
  double ropeLength = 1.0;      // m, > 0
  double topHeight = 3.0;       // m, > ropeLength: the top pin (the ground is y = 0)
  double boxMass = 2.0;         // kg, > 0
  double boxHalfExtent = 0.08;  // m, > 0 (a cube)
  double swingAngle = 0.5;      // rad, in [0, 1.5]: the pendulum is released at this angle
  double cutTime = 1.0;         // s, >= 0
  double cutFraction = 0.5;     // in (0, 1): where along the rope it is cut
  double timeStep = 1.0 / 240.0;  // s, > 0
  RodSettings rod = defaultRod();
  bullet::BulletRopeSettings bridge;
  bullet::AttachmentSettings attachment;

  static RodSettings defaultRod();  // the crane's rope: 0.01 kg/m, radius 4 mm, EA = 25 kN
};

class CutScene : public WorldScene {
 public:
  explicit CutScene(const CutSceneSettings& settings);

  StepMeasurements step() override;
  StepMeasurements measure() const override;
  void draw(render::Scene& scene) const override;
  std::optional<render::Camera> camera() const override;

  const bullet::RopeObject& upper() const { return *rig_.rope; }
  // The lower piece after the cut, nullptr before.
  const bullet::RopeObject* lower() const { return lower_.get(); }
  const btRigidBody& box() const { return *rig_.box; }
  bool isCut() const { return lower_ != nullptr; }
  // Distance of the upper piece's top from its pin, m.
  double pinGap() const;

 private:
  CutSceneSettings settings_;
  HangingBox rig_;  // its rope is the whole rope before the cut, the upper piece after
  std::unique_ptr<bullet::RopeObject> lower_;
  btVector3 pin_{0, 0, 0};
};

}  // namespace rope::demos
