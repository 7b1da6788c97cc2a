// SPDX-License-Identifier: MIT
#pragma once
// A DemoScene built from a scene file (scene_description.h): a PhysicsWorld with the file's bodies
// and ropes, stepped at the file's time step with one Bullet substep per step, its scripted events
// (keyframes, forces, velocities, cuts, releases, winches) applied before the step they fall in, and
// its checks (scene_checks.h) evaluated after every step. A failing rope step does not throw here
// (the ropes keep their last good state and count it, rope_warnings.h): a `health` check turns it
// into a failed verdict.

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bullet_bridge/rope_object.h"
#include "demos/scene_file/bullet_file_import.h"
#include "demos/scene_file/scene_checks.h"
#include "demos/scene_file/scene_description.h"
#include "demos/scenes/demo_scene.h"
#include "demos/scenes/physics_world.h"

namespace rope::demos {

class FileScene : public DemoScene {
 public:
  // Builds the world. Throws SceneFileError naming the file's path of whatever the library rejects
  // (an s outside its rope, a pin where there is one already, ...). checksEnabled = false skips the
  // checks' evaluation (to measure what they cost).
  explicit FileScene(SceneDescription description, bool checksEnabled = true);
  ~FileScene() override;

  double timeStep() const override { return description_.timeStep; }
  StepMeasurements step() override;
  StepMeasurements measure() const override;
  void draw(render::Scene& scene) const override;
  void appendState(std::vector<double>& state) const override;
  std::optional<render::Camera> camera() const override;

  const SceneDescription& description() const { return description_; }
  double time() const { return static_cast<double>(steps_) * description_.timeStep; }
  long steps() const { return steps_; }
  PhysicsWorld& physics() { return physics_; }
  const PhysicsWorld& physics() const { return physics_; }
  // nullptr if there is no rope / body of that name (yet: a cut names its new piece).
  const bullet::RopeObject* findRope(const std::string& name) const;
  const btRigidBody* findBody(const std::string& name) const;
  // The id of the rope's named pin or attachment, if the rope still holds it.
  std::optional<int> attachmentId(const std::string& rope, const std::string& name) const;
  // The rope's parameter of a file's s ("begin", "end" or a number, which is the parameter itself).
  static double parameter(const bullet::RopeObject& rope, const RopeParameter& s);

  const SceneChecks& checks() const { return checks_; }
  SceneChecks& checks() { return checks_; }
  // Ends the checks' evaluation (SceneChecks::finish) at the current time.
  void finishChecks() { checks_.finish(time()); }

 private:
  struct RopeEntry {
    std::string name;
    std::unique_ptr<bullet::RopeObject> rope;
    std::map<std::string, int> ids;  // named pins and attachments
    bool showControlPolygon = false;
  };
  struct MovingPin {
    std::string rope;
    int id = 0;
    std::vector<Keyframe> keyframes;
  };
  struct OwnGravity {  // a dynamic body's own gravity (BT_DISABLE_WORLD_GRAVITY), ramped up from zero
    btRigidBody* body = nullptr;
    btVector3 gravity;      // m/s^2
    double rampTime = 0.0;  // s
    btVector3 at(double t) const;  // the gravity at time t
  };
  struct PendingWinch {
    std::string rope;
    WinchDescription winch;
    bool started = false;
  };
  void buildBody(const BodyDescription& body);
  void buildRope(const RopeDescription& rope, std::size_t index);
  void applyScript();  // events, keyframes and winches due before the next step
  void applyEvent(const EventDescription& event);
  RopeEntry& entry(const std::string& name);

  SceneDescription description_;
  PhysicsWorld physics_;
  std::vector<std::unique_ptr<BulletFileImport>> imports_;  // after physics_: they leave its world first
  std::map<std::string, btRigidBody*> bodies_;
  std::vector<std::pair<btRigidBody*, std::vector<Keyframe>>> kinematicBodies_;
  std::vector<RopeEntry> ropes_;
  std::vector<MovingPin> movingPins_;
  std::vector<PendingWinch> winches_;
  std::vector<OwnGravity> ownGravity_;
  std::vector<bool> eventDone_;
  long steps_ = 0;
  SceneChecks checks_;
  bool checksEnabled_ = true;
};

// The pose of keyframes at time t (held outside them), as a Bullet transform.
btTransform keyframePose(const std::vector<Keyframe>& keyframes, double t);

}  // namespace rope::demos
