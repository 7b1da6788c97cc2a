// SPDX-License-Identifier: MIT
#include "demos/scenes/drape_scene.h"

#include <algorithm>

#include "rope/common/error.h"

namespace rope::demos {

RodSettings DrapeSceneSettings::defaultRod() {
  RodSettings rod;
  rod.radius = 0.01;
  rod.youngsModulus = 2.0e8;
  rod.bendingStiffness = 1.0e-3;  // N m^2: a limp rope that drapes (the solid-rod value is 1.6 N m^2)
  // Not needed to come to rest (every check of drape.json and thinbar.json holds without it): the
  // comparison (demos/compare) gives the soft body and the MuJoCo chain this same mass damping.
  rod.massDamping = 0.2;
  rod.initialControlPoints = 16;
  return rod;
}

DrapeSceneSettings DrapeSceneSettings::thinBar() {
  DrapeSceneSettings settings;
  settings.obstacle = Obstacle::kThinBar;
  settings.obstacleTop = 1.0;
  settings.dropHeight = 1.0;
  return settings;
}

namespace {

double sampleHeight(const Rod& rod, bool lowest) {
  constexpr int kSamples = 200;
  double extreme = rod.position(rod.beginParameter()).y();
  for (int i = 1; i <= kSamples; ++i) {
    const double s = rod.beginParameter() + (rod.endParameter() - rod.beginParameter()) * i / kSamples;
    const double y = rod.position(std::min(s, rod.endParameter())).y();
    extreme = lowest ? std::min(extreme, y) : std::max(extreme, y);
  }
  return extreme;
}

}  // namespace

DrapeScene::DrapeScene(const DrapeSceneSettings& settings) : WorldScene("drape", settings.timeStep), settings_(settings) {
  requirePositive("settings.ropeLength", settings.ropeLength);
  requireNonNegative("settings.dropHeight", settings.dropHeight);
  requirePositive("settings.obstacleTop", settings.obstacleTop);
  requirePositive("settings.barThickness", settings.barThickness);
  requirePositive("settings.timeStep", settings.timeStep);
  physics_.addGround(0.0);
  if (settings.obstacle == DrapeSceneSettings::Obstacle::kBox) {
    const double half = 0.5 * settings.obstacleTop;
    obstacle_ = physics_.addBox(btVector3(btScalar(0.6), static_cast<btScalar>(half), btScalar(0.3)), 0.0,
                                btVector3(0, static_cast<btScalar>(half), 0));
  } else {
    const btScalar half = static_cast<btScalar>(0.5 * settings.barThickness);
    obstacle_ = physics_.addBox(btVector3(half, half, btScalar(0.3)), 0.0,
                                btVector3(0, static_cast<btScalar>(settings.obstacleTop) - half, 0));
  }
  RodSettings rod = settings.rod;
  rod.restLength = settings.ropeLength;
  const double y = settings.obstacleTop + settings.dropHeight + rod.radius;
  const double half = 0.5 * settings.ropeLength;
  rope_ = std::make_unique<bullet::RopeObject>(Rod::fromSegment(rod, Vec3(-half, y, 0.0), Vec3(half, y, 0.0)),
                                               settings.bridge);
  physics_.ropes().addRope(*rope_);
}

StepMeasurements DrapeScene::step() { return advance(); }

StepMeasurements DrapeScene::measure() const {
  StepMeasurements measurements = ropeMeasurements(physics_, *rope_);
  measurements.series = {{"contacts", static_cast<double>(rope_->lastStep().contacts)}, {"lowest_m", lowestPoint()}};
  return measurements;
}

double DrapeScene::lowestPoint() const { return sampleHeight(rope_->rod(), true); }
double DrapeScene::highestPoint() const { return sampleHeight(rope_->rod(), false); }

void DrapeScene::draw(render::Scene& scene) const {
  physics_.draw(scene);
  drawRope(scene, *rope_);
}

std::optional<render::Camera> DrapeScene::camera() const {
  render::Camera camera;
  camera.target = Vec3(0.0, settings_.obstacleTop - 0.1, 0.0);
  camera.eye = camera.target + Vec3(0.5, 0.45, 1.6);
  return camera;
}

}  // namespace rope::demos
