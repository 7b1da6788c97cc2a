// SPDX-License-Identifier: MIT
#pragma once
// "pile": a long rope dropped onto the ground piles up into a heap. It starts as a loose vertical coil
// (a helix whose turns are several diameters apart, tilted so that the turns land unevenly) above a
// ground plane, falls, and its turns collapse onto each other: many simultaneous self-contacts and
// ground contacts, the stress case for rope-rope contact (contact/rope_rope_contact.h).

#include <memory>

#include "bullet_bridge/rope_object.h"
#include "demos/scenes/world_scene.h"

namespace rope::demos {

struct PileSceneSettings {
  double ropeLength = 2.0;      // m, > 0
  double dropHeight = 0.5;      // m, > 0: height of the coil's lowest point above the ground
  double coilRadius = 0.06;     // m, > 0: radius of the helix the rope starts as
  double coilPitch = 0.04;      // m, > 0: rise per turn (at least 3 diameters: the turns start apart)
  double tilt = 0.3;            // rad, in [0, 1]: the coil's axis leans this far from the vertical
  double timeStep = 1.0 / 240.0;  // s, > 0
  RodSettings rod = defaultRod();
  bullet::BulletRopeSettings bridge = defaultBridge();

  // The knot scene's cord (5 mm radius, limp), more stiffness damping, up to 128 control points.
  static RodSettings defaultRod();
  static bullet::BulletRopeSettings defaultBridge();  // the knot scene's contact (1e4 N/m, mu 0.3)
};

// The initial coil as a polyline (m), one point per ~3 cm. Throws InvalidArgument naming the field.
PointList pileCoilPolyline(const PileSceneSettings& settings);

class PileScene : public WorldScene {
 public:
  explicit PileScene(const PileSceneSettings& settings);

  StepMeasurements step() override;
  StepMeasurements measure() const override;
  void draw(render::Scene& scene) const override;
  std::optional<render::Camera> camera() const override;

  const bullet::RopeObject& rope() const { return *rope_; }
  double heapHeight() const;  // m, highest point of the rope's centre line

 private:
  PileSceneSettings settings_;
  std::unique_ptr<bullet::RopeObject> rope_;
};

}  // namespace rope::demos
