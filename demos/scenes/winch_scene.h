// SPDX-License-Identifier: MIT
#pragma once
// "winch": a crane lowers a 10 kg box and lifts it back with a winch (winch.h). The rope's top end is
// held at the winch point (a world point on the crane's jib, attachToPoint) and its bottom end is
// attached to the box's top face (two-way). The box first settles; at lowerStart the winch pays out
// travel metres of rope at speed, holds for holdDuration, then reels the same length back in. In
// steady motion the winch tension is the weight below it, (M + mu L) g (docs/method.md eq. 49).

#include <memory>

#include "bullet_bridge/rope_object.h"
#include "demos/scenes/hanging_box.h"
#include "demos/scenes/world_scene.h"

namespace rope::demos {

struct WinchSceneSettings {
  double ropeLength = 1.0;        // m, > 0: rest length before lowering
  double winchHeight = 2.0;       // m, finite: the winch point (the ground is y = 0)
  double boxMass = 10.0;          // kg, > 0
  double boxHalfExtent = 0.1;     // m, > 0 (a cube)
  double lowerStart = 1.0;        // s, >= 0
  double travel = 0.5;            // m of rope paid out and reeled back in, > 0
  double speed = 0.1;             // m/s, in (0, kMaxWinchSpeed]
  double holdDuration = 1.0;      // s, >= 0: pause at the bottom
  double timeStep = 1.0 / 240.0;  // s, > 0
  RodSettings rod = defaultRod();
  bullet::BulletRopeSettings bridge;
  bullet::AttachmentSettings attachment;

  // The crane scene's rope: 0.01 kg/m, radius 4 mm, E = 5e8 Pa (EA = 25.1 kN), damped bounce.
  static RodSettings defaultRod();
};

class WinchScene : public WorldScene {
 public:
  enum class Phase { kSettle, kLower, kHold, kLift, kDone };

  explicit WinchScene(const WinchSceneSettings& settings);

  StepMeasurements step() override;
  StepMeasurements measure() const override;
  void draw(render::Scene& scene) const override;
  std::optional<render::Camera> camera() const override;

  const bullet::RopeObject& rope() const { return *rig_.rope; }
  const btRigidBody& box() const { return *rig_.box; }
  Phase phase() const { return phase_; }
  // Tension at the winch, N (RopeObject::winchTension).
  double winchTension() const;
  // What it is in steady motion: the weight of the box and of the rope below the winch, N.
  double expectedTension() const;
  // Time the lowering starts, the lift starts, and both end, s (at the commanded speed).
  double lowerEnd() const { return settings_.lowerStart + settings_.travel / settings_.speed; }
  double liftStart() const { return lowerEnd() + settings_.holdDuration; }
  double liftEnd() const { return liftStart() + settings_.travel / settings_.speed; }

 private:
  WinchSceneSettings settings_;
  HangingBox rig_;
  Phase phase_ = Phase::kSettle;
};

}  // namespace rope::demos
