// SPDX-License-Identifier: MIT
#include "demos/scenes/crane_scene.h"

#include <cmath>

#include "rope/common/error.h"

namespace rope::demos {

RodSettings CraneSceneSettings::defaultRod() {
  RodSettings rod;
  rod.radius = 0.004;
  rod.linearDensity = 0.01;
  rod.youngsModulus = 5.0e8;
  // Damping the defaults lack: without it the 10 kg box bounces on the rope's stretch (about 8 Hz) and
  // the top tension is 99.67 N at 6 s instead of the settled 98.2 N (measured 2026-11-28). Shared by
  // the winch and cut scenes, whose box hangs on the same rope.
  rod.massDamping = 0.5;
  rod.stiffnessDamping = 0.01;
  rod.initialControlPoints = 12;
  return rod;
}

CraneScene::CraneScene(const CraneSceneSettings& settings) : WorldScene("crane", settings.timeStep), settings_(settings) {
  requirePositive("settings.ropeLength", settings.ropeLength);
  requireFinite("settings.topHeight", settings.topHeight);
  requirePositive("settings.boxMass", settings.boxMass);
  requirePositive("settings.boxHalfExtent", settings.boxHalfExtent);
  requireNonNegative("settings.liftStart", settings.liftStart);
  requireFinite("settings.liftHeight", settings.liftHeight);
  requirePositive("settings.liftDuration", settings.liftDuration);
  requirePositive("settings.timeStep", settings.timeStep);
  physics_.addGround(0.0);
  rig_ = hangBox(physics_,
                 {settings.ropeLength, settings.boxMass, settings.boxHalfExtent, settings.rod, settings.bridge,
                  settings.attachment},
                 Vec3(0.0, settings.topHeight, 0.0), Vec3(0.0, settings.topHeight - settings.ropeLength, 0.0));
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
  const double next = static_cast<double>(++steps_) * settings_.timeStep;  // counted, not summed: no drift
  rig_.rope->setAttachmentTarget(rig_.pin, btVector3(0, static_cast<btScalar>(topHeight(next)), 0));
  return advance(next);
}

StepMeasurements CraneScene::measure() const {
  StepMeasurements measurements = ropeMeasurements(physics_, rope());
  measurements.series = {{"box_y_m", static_cast<double>(box().getCenterOfMassPosition().y())},
                         {"attachment_gap_m", attachmentGap()},
                         {"expected_strain", expectedStrain()}};
  return measurements;
}

double CraneScene::attachmentGap() const {
  const btVector3 point =
      box().getCenterOfMassTransform() * btVector3(0, static_cast<btScalar>(settings_.boxHalfExtent), 0);
  return (rope().rod().position(rope().rod().endParameter()) - toVec3(point)).norm();
}

double CraneScene::expectedStrain() const {
  const double weight = settings_.boxMass * rope().rod().settings().gravity.norm();
  return weight / rope().rod().settings().axialStiffness();
}

void CraneScene::draw(render::Scene& scene) const {
  physics_.draw(scene);
  drawRope(scene, rope());
}

std::optional<render::Camera> CraneScene::camera() const {
  render::Camera camera;
  camera.target = Vec3(0.0, settings_.topHeight - 0.6 * settings_.ropeLength, 0.0);
  camera.eye = camera.target + Vec3(0.8, 0.4, 2.4);
  return camera;
}

}  // namespace rope::demos
