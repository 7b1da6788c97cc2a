// SPDX-License-Identifier: MIT
#include "demos/scenes/crane_scene.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "demos/scenes/scene_state.h"
#include "rope/common/error.h"

namespace rope::demos {

RodSettings CraneSceneSettings::defaultRod() {
  RodSettings rod;
  rod.radius = 0.004;
  rod.linearDensity = 0.01;
  rod.youngsModulus = 5.0e8;
  rod.massDamping = 0.5;
  rod.stiffnessDamping = 0.01;
  rod.initialControlPoints = 12;
  return rod;
}

CraneScene::CraneScene(const CraneSceneSettings& settings) : settings_(settings) {
  requirePositive("settings.ropeLength", settings.ropeLength);
  requireFinite("settings.topHeight", settings.topHeight);
  requirePositive("settings.boxMass", settings.boxMass);
  requirePositive("settings.boxHalfExtent", settings.boxHalfExtent);
  requireNonNegative("settings.liftStart", settings.liftStart);
  requireFinite("settings.liftHeight", settings.liftHeight);
  requirePositive("settings.liftDuration", settings.liftDuration);
  requirePositive("settings.timeStep", settings.timeStep);
  physics_.addGround(0.0);
  const double boxTop = settings.topHeight - settings.ropeLength;
  const btScalar half = static_cast<btScalar>(settings.boxHalfExtent);
  box_ = physics_.addBox(btVector3(half, half, half), settings.boxMass,
                         btVector3(0, static_cast<btScalar>(boxTop) - half, 0));
  box_->setActivationState(DISABLE_DEACTIVATION);
  RodSettings rod = settings.rod;
  rod.restLength = settings.ropeLength;
  rope_ = std::make_unique<bullet::RopeObject>(
      Rod::fromSegment(rod, Vec3(0.0, settings.topHeight, 0.0), Vec3(0.0, boxTop, 0.0)), settings.bridge);
  physics_.ropes().addRope(*rope_);
  topAttachment_ = rope_->attachToPoint(rope_->rod().beginParameter(),
                                        btVector3(0, static_cast<btScalar>(settings.topHeight), 0));
  boxAttachment_ = rope_->attachToBody(rope_->rod().endParameter(), *box_, btVector3(0, half, 0), settings.attachment);
}

double CraneScene::topHeight(double t) const {
  if (t <= settings_.liftStart) return settings_.topHeight;
  const double u = std::min(1.0, (t - settings_.liftStart) / settings_.liftDuration);
  const double lifted = settings_.topHeight + settings_.liftHeight;
  // Smoothstep from the top's start to its end, written as a scene file's keyframes interpolate it
  // (demos/scenes/crane.json gives bitwise this scene's trajectory).
  return settings_.topHeight + u * u * (3.0 - 2.0 * u) * (lifted - settings_.topHeight);
}

StepMeasurements CraneScene::step() {
  const double next = static_cast<double>(steps_ + 1) * settings_.timeStep;  // counted, not summed: no drift
  rope_->setAttachmentTarget(topAttachment_, btVector3(0, static_cast<btScalar>(topHeight(next)), 0));
  const btScalar h = static_cast<btScalar>(settings_.timeStep);
  physics_.world().stepSimulation(h, 1, h);
  time_ = next;
  ++steps_;
  const bullet::RopeStepRecord& record = rope_->lastStep();
  if (!record.ok) throw std::runtime_error(std::string("crane: rope step failed: ") + record.failure);
  StepMeasurements measurements = measure();
  measurements.insertions = record.insertions;
  measurements.removals = record.removals;
  return measurements;
}

StepMeasurements CraneScene::measure() const {
  StepMeasurements measurements = ropeMeasurements(physics_, *rope_);
  measurements.series = {{"box_y_m", static_cast<double>(box_->getCenterOfMassPosition().y())},
                         {"attachment_gap_m", attachmentGap()},
                         {"expected_strain", expectedStrain()}};
  return measurements;
}

double CraneScene::attachmentGap() const {
  const btVector3 point =
      box_->getCenterOfMassTransform() * btVector3(0, static_cast<btScalar>(settings_.boxHalfExtent), 0);
  const Vec3 end = rope_->rod().position(rope_->rod().endParameter());
  return (end - Vec3(static_cast<double>(point.x()), static_cast<double>(point.y()), static_cast<double>(point.z())))
      .norm();
}

double CraneScene::expectedStrain() const {
  const double weight = settings_.boxMass * rope_->rod().settings().gravity.norm();
  return weight / rope_->rod().settings().axialStiffness();
}

void CraneScene::draw(render::Scene& scene) const {
  physics_.draw(scene);
  drawRope(scene, *rope_);
}

std::optional<render::Camera> CraneScene::camera() const {
  render::Camera camera;
  camera.target = Vec3(0.0, settings_.topHeight - 0.6 * settings_.ropeLength, 0.0);
  camera.eye = camera.target + Vec3(0.8, 0.4, 2.4);
  return camera;
}

void CraneScene::appendState(std::vector<double>& state) const {
  appendWorldState(physics_, state);
}

}  // namespace rope::demos
