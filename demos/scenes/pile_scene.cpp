// SPDX-License-Identifier: MIT
#include "demos/scenes/pile_scene.h"

#include <algorithm>
#include <cmath>

#include "demos/scenes/knot_scene.h"
#include "rope/common/error.h"
#include "rope/spline/arc_length.h"
#include "rope/spline/bspline_curve.h"
#include "rope/spline/curve_interpolation.h"

namespace rope::demos {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kPointSpacing = 0.03;  // m along the helix between polyline points

void validate(const PileSceneSettings& settings) {
  requirePositive("settings.ropeLength", settings.ropeLength);
  requirePositive("settings.dropHeight", settings.dropHeight);
  requirePositive("settings.coilRadius", settings.coilRadius);
  requirePositive("settings.coilPitch", settings.coilPitch);
  requireNonNegative("settings.tilt", settings.tilt);
  if (settings.tilt > 1.0) throw InvalidArgument("settings.tilt", formatValue(settings.tilt), "must be <= 1 rad");
  requirePositive("settings.timeStep", settings.timeStep);
  settings.rod.validate();
  settings.bridge.validate();
  if (settings.coilPitch < 6.0 * settings.rod.radius) {
    throw InvalidArgument("settings.coilPitch", formatValue(settings.coilPitch),
                          "must be at least 3 rope diameters (" + formatValue(6.0 * settings.rod.radius) + " m)");
  }
}

}  // namespace

RodSettings PileSceneSettings::defaultRod() {
  RodSettings rod = KnotSceneSettings::defaultRod();
  rod.maxControlPoints = 128;
  // Mass and stiffness damping for the impact of the falling coil, on top of the material damping:
  // one drop with stiffness damping 1e-3 s went 4.3 mm into the ground, overlapped itself by 1.6 mm
  // and stretched locally by 55 %, at 0.01 s 3.3 mm, 0.84 mm and 5.7 % (rms speed over 5.5-6 s 5.7
  // and 3.8 mm/s; without any damping 8.5 mm and 3.5 mm; 2026-11-28). With 1 ms of material damping
  // alone the five drops went 8.5 mm into the ground at the median (2026-11-29).
  rod.massDamping = 0.5;
  rod.stiffnessDamping = 0.01;
  return rod;
}

bullet::BulletRopeSettings PileSceneSettings::defaultBridge() { return KnotSceneSettings::defaultBridge(); }

PointList pileCoilPolyline(const PileSceneSettings& settings) {
  validate(settings);
  const double turnLength = std::hypot(2.0 * kPi * settings.coilRadius, settings.coilPitch);
  const int count = std::max(8, static_cast<int>(std::ceil(settings.ropeLength / kPointSpacing)));
  const double c = std::cos(settings.tilt), s = std::sin(settings.tilt);
  PointList points;
  // The rope is the spline through these points, unstretched: adjust the number of turns until that
  // spline (not the helix, nor the chords) is ropeLength long; three passes reach 1e-6.
  double turns = settings.ropeLength / turnLength;
  double lowest = 0.0;
  for (int pass = 0; pass < 3; ++pass) {
    points.clear();
    for (int i = 0; i <= count; ++i) {
      const double u = static_cast<double>(i) / count;
      const double angle = 2.0 * kPi * turns * u;
      const Vec3 local(settings.coilRadius * std::cos(angle), settings.coilPitch * turns * u,
                       settings.coilRadius * std::sin(angle));
      const Vec3 p(local.x(), c * local.y() - s * local.z(), s * local.y() + c * local.z());  // lean about x
      lowest = i == 0 ? p.y() : std::min(lowest, p.y());
      points.push_back(p);
    }
    turns *= settings.ropeLength / arcLength(interpolatePolyline(points, settings.rod.degree).curve);
  }
  for (Vec3& p : points) p.y() += settings.dropHeight + settings.rod.radius - lowest;
  return points;
}

PileScene::PileScene(const PileSceneSettings& settings) : WorldScene("pile", settings.timeStep), settings_(settings) {
  const PointList points = pileCoilPolyline(settings);  // validates
  physics_.addGround(0.0);
  rope_ = std::make_unique<bullet::RopeObject>(Rod::fromPolyline(settings.rod, points, Rod::RestShape::kAsGiven),
                                               settings.bridge);
  physics_.ropes().addRope(*rope_);
}

StepMeasurements PileScene::step() { return advance(); }

StepMeasurements PileScene::measure() const {
  const Rod& rod = rope_->rod();
  StepMeasurements measurements = ropeMeasurements(physics_, *rope_);
  measurements.series = {{"self_contacts", static_cast<double>(rope_->lastStep().ropeContacts)},
                         {"ground_contacts", static_cast<double>(rope_->lastStep().contacts)},
                         {"heap_height_m", heapHeight()},
                         {"kinetic_energy_j", rod.kineticEnergy()}};
  return measurements;
}

double PileScene::heapHeight() const {
  const Rod& rod = rope_->rod();
  constexpr int kSamples = 400;
  double highest = rod.position(rod.beginParameter()).y();
  int span = -1;  // the samples come in order: each span search starts from the last one's
  for (int i = 1; i <= kSamples; ++i) {
    const double s = std::min(rod.endParameter(), rod.beginParameter() + (rod.endParameter() - rod.beginParameter()) * i / kSamples);
    highest = std::max(highest, curvePositionNear(rod.knots(), rod.controlPoints(), s, span).y());
  }
  return highest;
}

void PileScene::draw(render::Scene& scene) const {
  physics_.draw(scene);
  drawRope(scene, *rope_);
}

std::optional<render::Camera> PileScene::camera() const {
  // Follows the rope's mean point down to the heap, which ends up about 15 cm across.
  const Rod& rod = rope_->rod();
  constexpr int kSamples = 64;
  Vec3 mean = Vec3::Zero();
  for (int i = 0; i <= kSamples; ++i) {
    mean += rod.position(std::min(rod.endParameter(), rod.beginParameter() + (rod.endParameter() - rod.beginParameter()) * i / kSamples));
  }
  render::Camera camera;
  camera.target = mean / (kSamples + 1);
  camera.eye = camera.target + Vec3(0.22, 0.2, 0.32);
  return camera;
}

}  // namespace rope::demos
