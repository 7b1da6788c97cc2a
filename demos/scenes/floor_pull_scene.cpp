// SPDX-License-Identifier: MIT
#include "demos/scenes/floor_pull_scene.h"

#include <algorithm>
#include <cmath>

#include "rope/common/error.h"

namespace rope::demos {

double FloorPullSceneSettings::coulombAcceleration() const {
  return std::max(0.0, pullAcceleration - friction * gravity);
}

namespace {

void validate(const FloorPullSceneSettings& settings) {
  requireNonNegative("settings.friction", settings.friction);
  if (!std::isfinite(settings.pullAcceleration)) {
    throw InvalidArgument("settings.pullAcceleration", formatValue(settings.pullAcceleration), "must be finite");
  }
  requirePositive("settings.gravity", settings.gravity);
  requirePositive("settings.ropeLength", settings.ropeLength);
  requirePositive("settings.timeStep", settings.timeStep);
  settings.rod.validate();
  settings.bridge.validate();
}

}  // namespace

FloorPullScene::FloorPullScene(const FloorPullSceneSettings& settings)
    : WorldScene("floorpull", settings.timeStep, btVector3(0, static_cast<btScalar>(-settings.gravity), 0)),
      settings_(settings) {
  validate(settings);
  // The floor: a 6 m x 2 m box whose top face is y = 0 (the rope slides about 0.5 m in the first second
  // at the default pull).
  // Friction 1: the contact's coefficient (the product, friction_combination.h) is the rope's mu.
  physics_.addBox(btVector3(3, btScalar(0.1), 1), 0.0, btVector3(0, btScalar(-0.1), 0))->setFriction(btScalar(1.0));
  RodSettings rod = settings.rod;
  rod.restLength = settings.ropeLength;
  bullet::BulletRopeSettings bridge = settings.bridge;
  bridge.friction = settings.friction;
  const double half = 0.5 * settings.ropeLength;
  // Lying on the floor: the centre line one radius above it.
  rope_ = std::make_unique<bullet::RopeObject>(
      Rod::fromSegment(rod, Vec3(-half, rod.radius, 0.0), Vec3(half, rod.radius, 0.0)), bridge);
  physics_.ropes().addRope(*rope_);
}

double FloorPullScene::speed() const { return rope_->rod().momentum().x() / rope_->rod().mass(); }

double FloorPullScene::centreOfMassX() const {
  // Midpoint rule in the curve parameter, which is rest arc length for a rope made from a segment:
  // uniform linear density, so the plain mean of the samples is the centre of mass.
  const Rod& rod = rope_->rod();
  constexpr int kSamples = 256;
  double sum = 0.0;
  for (int i = 0; i < kSamples; ++i) {
    sum += rod.position(rod.beginParameter() + (rod.endParameter() - rod.beginParameter()) * (i + 0.5) / kSamples).x();
  }
  return sum / kSamples;
}

StepMeasurements FloorPullScene::step() {
  // The pull, per metre of rest length (one substep per step: it acts for the whole step).
  const Rod& rod = rope_->rod();
  const double forcePerLength = rod.mass() / rod.restLength() * settings_.pullAcceleration;
  rope_->applyDistributedForce(rod.beginParameter(), rod.endParameter(),
                               btVector3(static_cast<btScalar>(forcePerLength), 0, 0));
  return advance();
}

StepMeasurements FloorPullScene::measure() const {
  StepMeasurements measurements = ropeMeasurements(physics_, *rope_);
  measurements.series = {{"speed_m_s", speed()},
                         {"coulomb_speed_m_s", settings_.coulombAcceleration() * time()},
                         {"contacts", static_cast<double>(rope_->lastStep().contacts)}};
  return measurements;
}

void FloorPullScene::draw(render::Scene& scene) const {
  physics_.draw(scene);
  drawRope(scene, *rope_, true);
}

std::optional<render::Camera> FloorPullScene::camera() const {
  render::Camera camera;
  camera.target = Vec3(centreOfMassX(), 0.0, 0.0);
  camera.eye = camera.target + Vec3(0.0, 0.5, 1.2);
  return camera;
}

}  // namespace rope::demos
