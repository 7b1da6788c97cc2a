// SPDX-License-Identifier: MIT
#include "demos/scenes/tractrix_scene.h"

#include <algorithm>
#include <cmath>

#include "demos/scenes/ground.h"
#include "demos/scenes/scene_state.h"
#include "render/rope_drawing.h"
#include "rope/common/error.h"

namespace rope::demos {

namespace {

constexpr double kPi = 3.14159265358979323846;

const TractrixSceneSettings& validated(const TractrixSceneSettings& settings) {
  requirePositive("settings.ropeLength", settings.ropeLength);
  requirePositive("settings.radius", settings.radius);
  requirePositive("settings.loopRadius", settings.loopRadius);
  requirePositive("settings.period", settings.period);
  requirePositive("settings.timeStep", settings.timeStep);
  requirePositive("settings.separation", settings.separation);
  if (settings.polylineSegments < 1) {
    throw InvalidArgument("settings.polylineSegments", std::to_string(settings.polylineSegments), "must be >= 1");
  }
  if (settings.splineSides < 3) {
    throw InvalidArgument("settings.splineSides", std::to_string(settings.splineSides), "must be >= 3");
  }
  return settings;
}

// The rope starts straight, trailing behind the leading end against the path's initial direction.
PointList initialShape(const TractrixScene& scene, const Vec3& centre, double length) {
  const Vec3 start = scene.pathPoint(centre, 0.0);
  const Vec3 ahead = scene.pathPoint(centre, 1e-3);
  const Vec3 back = (start - ahead).normalized();
  return {start, start + length * back};
}

TractrixSettings variantSettings(TractrixVariant variant, int sides) {
  TractrixSettings settings;
  settings.variant = variant;
  settings.segmentCount = sides;
  return settings;
}

}  // namespace

TractrixScene::TractrixScene(const TractrixSceneSettings& settings)
    : settings_(validated(settings)),
      polylineCentre_(-0.5 * settings.separation, settings.radius, 0.0),
      splineCentre_(0.5 * settings.separation, settings.radius, 0.0),
      polyline_(initialShape(*this, polylineCentre_, settings.ropeLength),
                variantSettings(TractrixVariant::kPolyline, settings.polylineSegments)),
      spline_(initialShape(*this, splineCentre_, settings.ropeLength),
              variantSettings(TractrixVariant::kSplineSubdivideMerge, settings.splineSides)) {}

Vec3 TractrixScene::pathPoint(const Vec3& centre, double t) const {
  // Figure eight (a Gerono lemniscate) in the ground plane: tight turns at both ends, a crossing in
  // the middle, so the ropes bend, straighten and bend the other way.
  const double phase = 2.0 * kPi * t / settings_.period;
  const double r = settings_.loopRadius;
  return centre + Vec3(r * std::sin(phase), 0.0, 0.6 * r * std::sin(phase) * std::cos(phase));
}

StepMeasurements TractrixScene::step() {
  time_ += settings_.timeStep;
  polyline_.moveLeadingEnd(pathPoint(polylineCentre_, time_));
  const TractrixStepReport& adaptive = spline_.moveLeadingEnd(pathPoint(splineCentre_, time_));
  StepMeasurements measurements = measure();
  measurements.insertions = adaptive.insertions;
  measurements.removals = adaptive.merges;
  double largestMergeError = 0.0;
  for (const MergeRecord& merge : adaptive.mergeRecords) {
    largestMergeError = std::max(largestMergeError, merge.chosenLengthError() / spline_.initialLength());
  }
  measurements.series.push_back({"largest_merge_relative_error_trx_sd_mrg", largestMergeError});
  return measurements;
}

StepMeasurements TractrixScene::measure() const {
  StepMeasurements measurements;
  measurements.controlPoints = spline_.controlPointCount();
  // Kinematic ropes do not stretch; their strain is the relative length error of the curve.
  measurements.maxStrain = std::max(std::abs(polyline_.lengthError()), std::abs(spline_.lengthError()));
  measurements.series = {{"length_error_trx", polyline_.lengthError()},
                         {"length_error_trx_sd_mrg", spline_.lengthError()},
                         {"control_points_trx", static_cast<double>(polyline_.controlPointCount())}};
  return measurements;
}

void TractrixScene::draw(render::Scene& scene) const {
  addGround(scene);
  render::RopeStyle polylineStyle;
  polylineStyle.tube.radius = settings_.radius;
  polylineStyle.tube.colour = render::Rgb(0.55f, 0.58f, 0.62f);
  polylineStyle.showControlPolygon = false;
  render::addRope(scene, polyline_.knots(), polyline_.controlPoints(), polylineStyle);

  render::RopeStyle splineStyle;
  splineStyle.tube.radius = settings_.radius;
  splineStyle.tube.alternateSpanColours = true;
  splineStyle.showControlPolygon = true;
  splineStyle.controlPolygon.lineRadius = 0.2 * settings_.radius;
  splineStyle.controlPolygon.pointRadius = 0.55 * settings_.radius;
  render::addRope(scene, spline_.knots(), spline_.controlPoints(), splineStyle);
}

std::optional<render::Camera> TractrixScene::camera() const {
  render::Camera camera;
  camera.target = Vec3(0.0, 0.0, 0.1);
  camera.eye = Vec3(0.0, 2.1, 2.4);
  return camera;
}

void TractrixScene::appendState(std::vector<double>& state) const {
  appendTractrixState(polyline_, state);
  appendTractrixState(spline_, state);
}

}  // namespace rope::demos
