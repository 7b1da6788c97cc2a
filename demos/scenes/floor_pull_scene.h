// SPDX-License-Identifier: MIT
#pragma once
// "floorpull": flat Coulomb friction. A straight rope lies along x on a large static box (top face
// y = 0) and is pulled along the floor by a distributed force F (N per rope) from t = 0, with friction
// mu (BulletRopeSettings::friction). Coulomb's law for the rope as a whole: it slides with
//   v(t) = (F - mu m g) / m * t   when F > mu m g,   and stays put (v = 0) when F <= mu m g.
//
// How the force is applied: as a user would, by RopeObject::applyDistributedForce over the whole
// rope before every step, F / L = (m / L) pullAcceleration newtons per metre along +x; the rope
// follows the world's gravity (9.81 m/s^2 down), so the floor's normal load is m g. Everything else
// is the library's defaults (RodSettings{}, BulletRopeSettings{}).

#include <memory>

#include "bullet_bridge/rope_object.h"
#include "demos/scenes/world_scene.h"

namespace rope::demos {

struct FloorPullSceneSettings {
  double friction = 0.5;          // mu, >= 0: the contact's coefficient (the floor's Bullet friction is 1)
  double pullAcceleration = 6.0;  // F / m, m/s^2, finite (along +x)
  double gravity = 9.81;          // g, m/s^2, > 0 (downwards, the world's and the rope's)
  double ropeLength = 1.0;        // m, > 0
  double timeStep = 1.0 / 240.0;  // s, > 0
  RodSettings rod;                // defaults; restLength is set by the scene, gravity is the world's
  bullet::BulletRopeSettings bridge;  // defaults; friction is overwritten by `friction` above

  // (F - mu m g) / m clamped at 0: the acceleration Coulomb's law predicts, m/s^2.
  double coulombAcceleration() const;
};

class FloorPullScene : public WorldScene {
 public:
  // Throws InvalidArgument naming the field for bad settings.
  explicit FloorPullScene(const FloorPullSceneSettings& settings);

  StepMeasurements step() override;
  StepMeasurements measure() const override;
  void draw(render::Scene& scene) const override;
  std::optional<render::Camera> camera() const override;

  const bullet::RopeObject& rope() const { return *rope_; }
  // Velocity of the rope's centre of mass along x (momentum / mass), m/s.
  double speed() const;
  // Position of the rope's centre of mass along x (mass-weighted mean of the curve), m.
  double centreOfMassX() const;

 private:
  FloorPullSceneSettings settings_;
  std::unique_ptr<bullet::RopeObject> rope_;
};

}  // namespace rope::demos
