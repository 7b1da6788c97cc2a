// SPDX-License-Identifier: MIT
#pragma once
// What every scene in a Bullet world (a PhysicsWorld) shares: the world, the fixed step, the clock,
// the step itself and the state the golden hash reads. A scene adds its bodies and ropes to physics_
// in its constructor and implements measure(), draw() and camera(); its step() gives the commands
// for the coming step (targets, pulls, cuts, winches) and then calls advance().

#include <string>
#include <vector>

#include "demos/scenes/demo_scene.h"
#include "demos/scenes/physics_world.h"

namespace rope::demos {

class WorldScene : public DemoScene {
 public:
  double timeStep() const override { return timeStep_; }
  // Every rigid body, then every rope of the RopeWorld (appendWorldState).
  void appendState(std::vector<double>& state) const override;

  PhysicsWorld& physics() { return physics_; }
  const PhysicsWorld& physics() const { return physics_; }
  double time() const { return time_; }  // s, simulated

 protected:
  // `name` starts the message of a failed step; timeStep in s (the scene validates it).
  WorldScene(std::string name, double timeStep, const btVector3& gravity = btVector3(0, btScalar(-9.81), 0));

  // Steps the world by timeStep() (stepAndCheck: throws std::runtime_error naming the scene if a
  // rope fails), sets the clock to `time` (s) and returns measure() with the step's knot counts.
  StepMeasurements advance(double time);
  // The same with the clock summed: time() + timeStep().
  StepMeasurements advance() { return advance(time_ + timeStep_); }

  PhysicsWorld physics_;

 private:
  std::string name_;
  double timeStep_;
  double time_ = 0.0;
};

}  // namespace rope::demos
