// SPDX-License-Identifier: MIT
#include "demos/scenes/hang_scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "demos/scenes/ground.h"
#include "demos/scenes/scene_state.h"
#include "render/rope_drawing.h"
#include "rope/common/error.h"

namespace rope::demos {

RodSettings HangSceneSettings::defaultRod() {
  RodSettings rod;
  rod.radius = 0.01;
  rod.youngsModulus = 2.0e8;
  // Not needed by the scene (its rope settles the same without it: kinetic energy 4e-17 J by 4 s either
  // way), but the comparison's catenary and scaling scenes use this rope and give the peers the same
  // damping; undamped, that rope (EI = 0) grows unstable at 256 and more fixed control points (README,
  // known limits). Measured 2026-11-28.
  rod.massDamping = 0.4;
  rod.initialControlPoints = 12;
  return rod;
}

namespace {

// Catenary parameter a with 2a sinh(D / 2a) = L (L > D), by Newton on x = D / 2a:
// sinh(x) / x = L / D, monotone increasing in x.
double catenaryParameter(double length, double span) {
  const double ratio = length / span;
  double x = std::sqrt(6.0 * (ratio - 1.0));  // series start: sinh(x)/x ~ 1 + x^2/6
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double f = std::sinh(x) / x - ratio;
    const double df = (x * std::cosh(x) - std::sinh(x)) / (x * x);
    const double next = x - f / df;
    if (std::abs(next - x) < 1e-15 * x) break;
    x = next;
  }
  return span / (2.0 * x);
}

}  // namespace

HangScene::HangScene(const HangSceneSettings& settings)
    : settings_(settings),
      rod_([&] {
        requirePositive("settings.span", settings.span);
        requirePositive("settings.ropeLength", settings.ropeLength);
        requireFinite("settings.pinHeight", settings.pinHeight);
        requireNonNegative("settings.closeTime", settings.closeTime);
        requirePositive("settings.timeStep", settings.timeStep);
        if (!(settings.span < settings.ropeLength)) {
          throw InvalidArgument("settings.span", formatValue(settings.span),
                                "must be < settings.ropeLength for a hanging catenary");
        }
        RodSettings rod = settings.rod;
        rod.restLength = settings.ropeLength;
        const double half = 0.5 * settings.ropeLength;
        return Rod::fromSegment(rod, Vec3(-half, settings.pinHeight, 0.0),
                                Vec3(half, settings.pinHeight, 0.0));
      }()) {
  leftPin_ = rod_.pin(rod_.beginParameter());
  rightPin_ = rod_.pin(rod_.endParameter());
}

double HangScene::pinDistance(double time) const {
  if (settings_.closeTime <= 0.0 || time >= settings_.closeTime) return settings_.span;
  // Smoothstep, so the pins start and stop without a jerk.
  const double u = time / settings_.closeTime;
  const double blend = u * u * (3.0 - 2.0 * u);
  return settings_.ropeLength + (settings_.span - settings_.ropeLength) * blend;
}

StepMeasurements HangScene::step() {
  const double next = time_ + settings_.timeStep;
  const double half = 0.5 * pinDistance(next);
  rod_.setPinTarget(leftPin_, Vec3(-half, settings_.pinHeight, 0.0));
  rod_.setPinTarget(rightPin_, Vec3(half, settings_.pinHeight, 0.0));
  const StepReport report = rod_.step(settings_.timeStep);
  if (!report.ok) throw std::runtime_error(std::string("hang: rod step failed: ") + report.failure);
  time_ = next;

  StepMeasurements measurements = measure();
  measurements.insertions = report.insertions;
  measurements.removals = report.removals;
  return measurements;
}

StepMeasurements HangScene::measure() const {
  StepMeasurements measurements;
  measurements.controlPoints = rod_.controlPointCount();
  measurements.maxStrain = rod_.maxStrain();
  measurements.series = {{"sag_m", sag()}, {"analytic_sag_m", analyticSag()}};
  return measurements;
}

double HangScene::sag() const {
  constexpr int kSamples = 400;
  double lowest = rod_.position(rod_.beginParameter()).y();
  const double s0 = rod_.beginParameter();
  const double s1 = rod_.endParameter();
  for (int i = 0; i <= kSamples; ++i) {
    const double s = s0 + (s1 - s0) * i / kSamples;
    lowest = std::min(lowest, rod_.position(std::min(s, s1)).y());
  }
  return settings_.pinHeight - lowest;
}

double HangScene::analyticSag() const {
  const double a = catenaryParameter(settings_.ropeLength, settings_.span);
  return a * (std::cosh(settings_.span / (2.0 * a)) - 1.0);
}

void HangScene::draw(render::Scene& scene) const {
  addGround(scene);
  render::RopeStyle style;
  style.tube.radius = settings_.rod.radius;
  style.tube.alternateSpanColours = true;
  style.showControlPolygon = true;
  style.controlPolygon.lineRadius = 0.25 * settings_.rod.radius;
  style.controlPolygon.pointRadius = 0.6 * settings_.rod.radius;
  render::addRope(scene, rod_.knots(), rod_.controlPoints(), style);
}

std::optional<render::Camera> HangScene::camera() const {
  render::Camera camera;
  const double reach = 0.5 * settings_.ropeLength;
  camera.target = Vec3(0.0, settings_.pinHeight - 0.45 * reach, 0.0);
  camera.eye = camera.target + Vec3(0.35, 0.25, 2.6) * reach;
  return camera;
}

void HangScene::appendState(std::vector<double>& state) const {
  appendRodState(rod_, state);
}

}  // namespace rope::demos
