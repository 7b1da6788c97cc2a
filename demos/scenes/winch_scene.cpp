// SPDX-License-Identifier: MIT
#include "demos/scenes/winch_scene.h"

#include <stdexcept>
#include <string>

#include "demos/scenes/crane_scene.h"
#include "demos/scenes/scene_state.h"
#include "rope/common/error.h"

namespace rope::demos {

RodSettings WinchSceneSettings::defaultRod() { return CraneSceneSettings::defaultRod(); }

WinchScene::WinchScene(const WinchSceneSettings& settings) : settings_(settings) {
  requirePositive("settings.ropeLength", settings.ropeLength);
  requireFinite("settings.winchHeight", settings.winchHeight);
  requirePositive("settings.boxMass", settings.boxMass);
  requirePositive("settings.boxHalfExtent", settings.boxHalfExtent);
  requireNonNegative("settings.lowerStart", settings.lowerStart);
  requirePositive("settings.travel", settings.travel);
  requirePositive("settings.speed", settings.speed);
  if (!(settings.speed <= bullet::kMaxWinchSpeed)) {
    throw InvalidArgument("settings.speed", formatValue(settings.speed), "must be <= kMaxWinchSpeed");
  }
  requireNonNegative("settings.holdDuration", settings.holdDuration);
  requirePositive("settings.timeStep", settings.timeStep);
  physics_.addGround(0.0);
  const double boxTop = settings.winchHeight - settings.ropeLength;
  const btScalar half = static_cast<btScalar>(settings.boxHalfExtent);
  box_ = physics_.addBox(btVector3(half, half, half), settings.boxMass,
                         btVector3(0, static_cast<btScalar>(boxTop) - half, 0));
  box_->setActivationState(DISABLE_DEACTIVATION);
  RodSettings rod = settings.rod;
  rod.restLength = settings.ropeLength;
  rope_ = std::make_unique<bullet::RopeObject>(
      Rod::fromSegment(rod, Vec3(0.0, settings.winchHeight, 0.0), Vec3(0.0, boxTop, 0.0)), settings.bridge);
  physics_.ropes().addRope(*rope_);
  rope_->attachToPoint(rope_->rod().beginParameter(), btVector3(0, static_cast<btScalar>(settings.winchHeight), 0));
  rope_->attachToBody(rope_->rod().endParameter(), *box_, btVector3(0, half, 0), settings.attachment);
}

StepMeasurements WinchScene::step() {
  const double next = time_ + settings_.timeStep;
  // Commands are given before the step that crosses their time (winch.h: they act from the next substep).
  if (phase_ == Phase::kSettle && next > settings_.lowerStart) {
    rope_->winchTo(bullet::RopeEnd::kBegin, settings_.ropeLength + settings_.travel, settings_.speed);
    phase_ = Phase::kLower;
  } else if (phase_ == Phase::kLower && rope_->winch(bullet::RopeEnd::kBegin).speed == 0.0) {
    phase_ = Phase::kHold;
  } else if (phase_ == Phase::kHold && next > liftStart()) {
    rope_->winchTo(bullet::RopeEnd::kBegin, settings_.ropeLength, settings_.speed);
    phase_ = Phase::kLift;
  } else if (phase_ == Phase::kLift && rope_->winch(bullet::RopeEnd::kBegin).speed == 0.0) {
    phase_ = Phase::kDone;
  }
  const btScalar h = static_cast<btScalar>(settings_.timeStep);
  physics_.world().stepSimulation(h, 1, h);
  time_ = next;
  const bullet::RopeStepRecord& record = rope_->lastStep();
  if (!record.ok) throw std::runtime_error(std::string("winch: rope step failed: ") + record.failure);
  StepMeasurements measurements = measure();
  measurements.insertions = record.insertions;
  measurements.removals = record.removals;
  return measurements;
}

double WinchScene::winchTension() const { return rope_->winchTension(bullet::RopeEnd::kBegin); }

double WinchScene::expectedTension() const {
  const Rod& rod = rope_->rod();
  return (settings_.boxMass + rod.mass()) * rod.settings().gravity.norm();
}

StepMeasurements WinchScene::measure() const {
  StepMeasurements measurements = ropeMeasurements(physics_, *rope_);
  measurements.series = {{"winch_tension_N", winchTension()},
                         {"expected_tension_N", expectedTension()},
                         {"rope_rest_length_m", rope_->rod().restLength()},
                         {"box_y_m", static_cast<double>(box_->getCenterOfMassPosition().y())}};
  return measurements;
}

void WinchScene::draw(render::Scene& scene) const {
  physics_.draw(scene);
  drawRope(scene, *rope_);
}

std::optional<render::Camera> WinchScene::camera() const {
  render::Camera camera;
  camera.target = Vec3(0.0, settings_.winchHeight - 0.8 * (settings_.ropeLength + settings_.travel), 0.0);
  camera.eye = camera.target + Vec3(1.0, 0.5, 3.0);
  return camera;
}

void WinchScene::appendState(std::vector<double>& state) const {
  appendWorldState(physics_, state);
}

}  // namespace rope::demos
