// SPDX-License-Identifier: MIT
#include "demos/scenes/winch_scene.h"

#include "demos/scenes/crane_scene.h"
#include "rope/common/error.h"

namespace rope::demos {

RodSettings WinchSceneSettings::defaultRod() { return CraneSceneSettings::defaultRod(); }

WinchScene::WinchScene(const WinchSceneSettings& settings) : WorldScene("winch", settings.timeStep), settings_(settings) {
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
  rig_ = hangBox(physics_,
                 {settings.ropeLength, settings.boxMass, settings.boxHalfExtent, settings.rod, settings.bridge,
                  settings.attachment},
                 Vec3(0.0, settings.winchHeight, 0.0), Vec3(0.0, settings.winchHeight - settings.ropeLength, 0.0));
}

StepMeasurements WinchScene::step() {
  const double next = time() + settings_.timeStep;
  // Commands are given before the step that crosses their time (winch.h: they act from the next substep).
  if (phase_ == Phase::kSettle && next > settings_.lowerStart) {
    rig_.rope->winchTo(bullet::RopeEnd::kBegin, settings_.ropeLength + settings_.travel, settings_.speed);
    phase_ = Phase::kLower;
  } else if (phase_ == Phase::kLower && rig_.rope->winch(bullet::RopeEnd::kBegin).speed == 0.0) {
    phase_ = Phase::kHold;
  } else if (phase_ == Phase::kHold && next > liftStart()) {
    rig_.rope->winchTo(bullet::RopeEnd::kBegin, settings_.ropeLength, settings_.speed);
    phase_ = Phase::kLift;
  } else if (phase_ == Phase::kLift && rig_.rope->winch(bullet::RopeEnd::kBegin).speed == 0.0) {
    phase_ = Phase::kDone;
  }
  return advance(next);
}

double WinchScene::winchTension() const { return rope().winchTension(bullet::RopeEnd::kBegin); }

double WinchScene::expectedTension() const {
  const Rod& rod = rope().rod();
  return (settings_.boxMass + rod.mass()) * rod.settings().gravity.norm();
}

StepMeasurements WinchScene::measure() const {
  StepMeasurements measurements = ropeMeasurements(physics_, rope());
  measurements.series = {{"winch_tension_N", winchTension()},
                         {"expected_tension_N", expectedTension()},
                         {"rope_rest_length_m", rope().rod().restLength()},
                         {"box_y_m", static_cast<double>(box().getCenterOfMassPosition().y())}};
  return measurements;
}

void WinchScene::draw(render::Scene& scene) const {
  physics_.draw(scene);
  drawRope(scene, rope());
}

std::optional<render::Camera> WinchScene::camera() const {
  render::Camera camera;
  camera.target = Vec3(0.0, settings_.winchHeight - 0.8 * (settings_.ropeLength + settings_.travel), 0.0);
  camera.eye = camera.target + Vec3(1.0, 0.5, 3.0);
  return camera;
}

}  // namespace rope::demos
