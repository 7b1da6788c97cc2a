// SPDX-License-Identifier: MIT
#include "demos/scenes/cut_scene.h"

#include <algorithm>
#include <cmath>

#include "demos/scenes/crane_scene.h"
#include "demos/scenes/scene_state.h"
#include "rope/common/error.h"

namespace rope::demos {

namespace {

btVector3 toBullet(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()), static_cast<btScalar>(v.z()));
}

}  // namespace

RodSettings CutSceneSettings::defaultRod() { return CraneSceneSettings::defaultRod(); }

CutScene::CutScene(const CutSceneSettings& settings) : settings_(settings) {
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
  const btScalar half = static_cast<btScalar>(settings.boxHalfExtent);
  box_ = physics_.addBox(btVector3(half, half, half), settings.boxMass, toBullet(end) - btVector3(0, half, 0));
  box_->setActivationState(DISABLE_DEACTIVATION);
  RodSettings rod = settings.rod;
  rod.restLength = settings.ropeLength;
  upper_ = std::make_unique<bullet::RopeObject>(Rod::fromSegment(rod, top, end), settings.bridge);
  physics_.ropes().addRope(*upper_);
  pin_ = toBullet(top);
  upper_->attachToPoint(upper_->rod().beginParameter(), pin_);
  upper_->attachToBody(upper_->rod().endParameter(), *box_, btVector3(0, half, 0), settings.attachment);
}

StepMeasurements CutScene::step() {
  if (!isCut() && time_ + 0.5 * settings_.timeStep >= settings_.cutTime) {
    const Rod& rod = upper_->rod();
    lower_ = upper_->cut(rod.beginParameter() + settings_.cutFraction * (rod.endParameter() - rod.beginParameter()));
  }
  const StepMeasurements counts = stepAndCheck(physics_, settings_.timeStep, "cut");
  time_ += settings_.timeStep;
  StepMeasurements measurements = measure();
  measurements.insertions = counts.insertions;
  measurements.removals = counts.removals;
  return measurements;
}

StepMeasurements CutScene::measure() const {
  StepMeasurements measurements;
  measurements.controlPoints = upper_->rod().controlPointCount() + (lower_ ? lower_->rod().controlPointCount() : 0);
  measurements.maxStrain = std::max(upper_->rod().maxStrain(), lower_ ? lower_->rod().maxStrain() : 0.0);
  measurements.maxPenetration = physics_.ropes().lastReport().maxPenetration();
  measurements.maxSelfOverlap = physics_.ropes().lastReport().maxSelfOverlap();
  measurements.series = {{"box_y_m", static_cast<double>(box_->getCenterOfMassPosition().y())},
                         {"box_vy_m_per_s", static_cast<double>(box_->getLinearVelocity().y())},
                         {"pieces", isCut() ? 2.0 : 1.0},
                         {"pin_gap_m", pinGap()}};
  return measurements;
}

double CutScene::pinGap() const {
  return (upper_->rod().position(upper_->rod().beginParameter()) -
          Vec3(static_cast<double>(pin_.x()), static_cast<double>(pin_.y()), static_cast<double>(pin_.z())))
      .norm();
}

void CutScene::draw(render::Scene& scene) const {
  physics_.draw(scene);
  drawRope(scene, *upper_);
  if (lower_) drawRope(scene, *lower_);
}

std::optional<render::Camera> CutScene::camera() const {
  render::Camera camera;
  camera.target = Vec3(0.2, settings_.topHeight - 0.9 * settings_.ropeLength, 0.0);
  camera.eye = camera.target + Vec3(0.4, 0.3, 2.6);
  return camera;
}

void CutScene::appendState(std::vector<double>& state) const {
  appendWorldState(physics_, state);
}

}  // namespace rope::demos
