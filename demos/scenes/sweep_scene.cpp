// SPDX-License-Identifier: MIT
#include "demos/scenes/sweep_scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "demos/scenes/scene_state.h"
#include "render/rope_drawing.h"
#include "rope/common/error.h"

namespace rope::demos {

namespace {

void validate(const SweepSceneSettings& settings) {
  requirePositive("settings.ropeLength", settings.ropeLength);
  requirePositive("settings.radius", settings.radius);
  requirePositive("settings.circleRadius", settings.circleRadius);
  requirePositive("settings.speed", settings.speed);
  if (settings.boxesPerSide < 1 || settings.boxesPerSide > 20) {
    throw InvalidArgument("settings.boxesPerSide", std::to_string(settings.boxesPerSide), "must be in [1, 20]");
  }
  requirePositive("settings.boxHalfExtent", settings.boxHalfExtent);
  requirePositive("settings.boxSpacing", settings.boxSpacing);
  if (!(settings.boxSpacing > 2.0 * settings.boxHalfExtent)) {
    throw InvalidArgument("settings.boxSpacing", formatValue(settings.boxSpacing), "must exceed two box half extents");
  }
  requirePositive("settings.boxMass", settings.boxMass);
  requirePositive("settings.timeStep", settings.timeStep);
}

}  // namespace

SweepScene::SweepScene(const SweepSceneSettings& settings) : WorldScene("sweep", settings.timeStep), settings_(settings) {
  validate(settings);
  physics_.addGround(0.0);
  // The field straddles the circle's rim at x = circleRadius, so the hose crosses it twice a turn.
  const btScalar half = static_cast<btScalar>(settings.boxHalfExtent);
  const double extent = settings.boxSpacing * (settings.boxesPerSide - 1);
  for (int i = 0; i < settings.boxesPerSide; ++i) {
    for (int k = 0; k < settings.boxesPerSide; ++k) {
      const btVector3 origin(static_cast<btScalar>(settings.circleRadius - 0.5 * extent + settings.boxSpacing * i), half,
                             static_cast<btScalar>(0.25 + settings.boxSpacing * k - 0.5 * extent));
      btRigidBody* box = physics_.addBox(btVector3(half, half, half), settings.boxMass, origin);
      box->setActivationState(DISABLE_DEACTIVATION);
      boxes_.push_back(box);
      starts_.push_back(origin);
    }
  }
  // Straight, trailing behind the leading end (which starts on the circle and heads along +z).
  const btVector3 start = path(0.0);
  const Vec3 lead(static_cast<double>(start.x()), static_cast<double>(start.y()), static_cast<double>(start.z()));
  TractrixSettings tractrix;  // TRX_SD_MRG, [B]'s 140/160 degrees
  bullet::KinematicRopeSettings hose;
  hose.radius = settings.radius;
  rope_ = std::make_unique<bullet::KinematicRope>(
      TractrixRope({lead, lead - Vec3(0.0, 0.0, settings.ropeLength)}, tractrix), hose);
  rope_->addToWorld(physics_.world());
  rope_->followPath([this](double t) { return path(t); });
}

SweepScene::~SweepScene() { rope_->removeFromWorld(); }

btVector3 SweepScene::path(double t) const {
  const double angle = settings_.speed * t / settings_.circleRadius;
  return btVector3(static_cast<btScalar>(settings_.circleRadius * std::cos(angle)), static_cast<btScalar>(settings_.radius),
                   static_cast<btScalar>(settings_.circleRadius * std::sin(angle)));
}

double SweepScene::largestBoxDisplacement() const {
  double largest = 0.0;
  for (std::size_t i = 0; i < boxes_.size(); ++i) {
    largest = std::max(largest, static_cast<double>((boxes_[i]->getCenterOfMassPosition() - starts_[i]).length()));
  }
  return largest;
}

StepMeasurements SweepScene::step() {
  // The hose is a kinematic rope, not one of the RopeWorld's: its own report says whether it failed
  // and how its polygon adapted.
  StepMeasurements measurements = advance();
  if (rope_->lastStep().targetFailure != nullptr && *rope_->lastStep().targetFailure != '\0') {
    throw std::runtime_error(std::string("sweep: ") + rope_->lastStep().targetFailure);
  }
  measurements.insertions = rope_->tractrix().lastReport().insertions;
  measurements.removals = rope_->tractrix().lastReport().merges;
  return measurements;
}

StepMeasurements SweepScene::measure() const {
  StepMeasurements measurements;
  const TractrixRope& tractrix = rope_->tractrix();
  measurements.controlPoints = static_cast<int>(tractrix.controlPoints().size());
  measurements.maxPenetration = rope_->lastStep().maxPenetration;
  measurements.series = {{"length_error", tractrix.lastReport().lengthError},
                         {"pushed_contacts", static_cast<double>(rope_->lastStep().contacts.size())},
                         {"largest_box_displacement_m", largestBoxDisplacement()}};
  return measurements;
}

void SweepScene::draw(render::Scene& scene) const {
  physics_.draw(scene);
  render::RopeStyle style;
  style.tube.radius = settings_.radius;
  style.tube.alternateSpanColours = true;
  render::addRope(scene, rope_->tractrix().knots(), rope_->tractrix().controlPoints(), style);
}

std::optional<render::Camera> SweepScene::camera() const {
  render::Camera camera;
  camera.target = Vec3(0.0, 0.0, 0.0);
  camera.eye = Vec3(0.9, 1.3, 1.9);
  return camera;
}

void SweepScene::appendState(std::vector<double>& state) const {
  WorldScene::appendState(state);
  appendTractrixState(rope_->tractrix(), state);
}

}  // namespace rope::demos
