// SPDX-License-Identifier: MIT
#include "demos/scenes/cut_scene.h"

#include <algorithm>
#include <cmath>

#include "demos/scenes/crane_scene.h"
#include "rope/common/error.h"

namespace rope::demos {

RodSettings CutSceneSettings::defaultRod() { return CraneSceneSettings::defaultRod(); }

CutScene::CutScene(const CutSceneSettings& settings) : WorldScene("cut", settings.timeStep), settings_(settings) {
  requirePositive("settings.ropeLength", settings.ropeLength);
  requireFinite("settings.topHeight", settings.topHeight);
  if (!(settings.topHeight > settings.ropeLength)) {
    throw InvalidArgument("settings.topHeight", formatValue(settings.topHeight), "must exceed settings.ropeLength");
  }
  requirePositive("settings.boxMass", settings.boxMass);
  requirePositive("settings.boxHalfExtent", settings.boxHalfExtent);
  requireNonNegative("settings.swingAngle", settings.swingAngle);
  if (settings.swingAngle > 1.5) throw InvalidArgument("settings.swingAngle", formatValue(settings.swingAngle), "must be <= 1.5 rad");
  requireNonNegative("settings.cutTime", settings.cutTime);
  requirePositive("settings.cutFraction", settings.cutFraction);
  if (!(settings.cutFraction < 1.0)) {
    throw InvalidArgument("settings.cutFraction", formatValue(settings.cutFraction), "must be < 1");
  }
  requirePositive("settings.timeStep", settings.timeStep);
  physics_.addGround(0.0);
  const Vec3 top(0.0, settings.topHeight, 0.0);
  const Vec3 end = top + settings.ropeLength * Vec3(std::sin(settings.swingAngle), -std::cos(settings.swingAngle), 0.0);
  rig_ = hangBox(physics_,
                 {settings.ropeLength, settings.boxMass, settings.boxHalfExtent, settings.rod, settings.bridge,
                  settings.attachment},
                 top, end);
  pin_ = toBullet(top);
}

StepMeasurements CutScene::step() {
  if (!isCut() && time() + 0.5 * settings_.timeStep >= settings_.cutTime) {
    const Rod& rod = upper().rod();
    lower_ = rig_.rope->cut(rod.beginParameter() + settings_.cutFraction * (rod.endParameter() - rod.beginParameter()));
  }
  return advance();
}

StepMeasurements CutScene::measure() const {
  StepMeasurements measurements;
  measurements.controlPoints = upper().rod().controlPointCount() + (lower_ ? lower_->rod().controlPointCount() : 0);
  measurements.maxStrain = std::max(upper().rod().maxStrain(), lower_ ? lower_->rod().maxStrain() : 0.0);
  measurements.maxPenetration = physics_.ropes().lastReport().maxPenetration();
  measurements.maxSelfOverlap = physics_.ropes().lastReport().maxSelfOverlap();
  measurements.series = {{"box_y_m", static_cast<double>(box().getCenterOfMassPosition().y())},
                         {"box_vy_m_per_s", static_cast<double>(box().getLinearVelocity().y())},
                         {"pieces", isCut() ? 2.0 : 1.0},
                         {"pin_gap_m", pinGap()}};
  return measurements;
}

double CutScene::pinGap() const {
  return (upper().rod().position(upper().rod().beginParameter()) - toVec3(pin_)).norm();
}

void CutScene::draw(render::Scene& scene) const {
  physics_.draw(scene);
  drawRope(scene, upper());
  if (lower_) drawRope(scene, *lower_);
}

std::optional<render::Camera> CutScene::camera() const {
  render::Camera camera;
  camera.target = Vec3(0.2, settings_.topHeight - 0.9 * settings_.ropeLength, 0.0);
  camera.eye = camera.target + Vec3(0.4, 0.3, 2.6);
  return camera;
}

}  // namespace rope::demos
