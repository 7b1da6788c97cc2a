// SPDX-License-Identifier: MIT
#include "demos/scenes/resting_rope_scene.h"

#include <algorithm>
#include <cmath>

#include "rope/common/error.h"

namespace rope::demos {

namespace {

using Settings = RestingRopeSceneSettings;

void validate(const Settings& settings) {
  if (settings.ropeCount < 1) {
    throw InvalidArgument("settings.ropeCount", std::to_string(settings.ropeCount), "must be >= 1");
  }
  requirePositive("settings.ropeLength", settings.ropeLength);
  requirePositive("settings.spacing", settings.spacing);
  requireNonNegative("settings.gap", settings.gap);
  requirePositive("settings.timeStep", settings.timeStep);
  settings.rod.validate();
  settings.bridge.validate();
  if (settings.spacing <= 2.0 * settings.rod.radius) {
    throw InvalidArgument("settings.spacing", formatValue(settings.spacing), "must exceed the rope's diameter");
  }
}

// A flat grid of squares of `cell` m, two triangles each, in the plane y = 0 over [-hx, hx] x [-hz, hz].
std::unique_ptr<btTriangleMesh> flatGrid(double hx, double hz, double cell) {
  auto mesh = std::make_unique<btTriangleMesh>();
  const int nx = static_cast<int>(std::ceil(2.0 * hx / cell));
  const int nz = static_cast<int>(std::ceil(2.0 * hz / cell));
  auto vertex = [&](int i, int k) {
    return btVector3(static_cast<btScalar>(-hx + 2.0 * hx * i / nx), 0, static_cast<btScalar>(-hz + 2.0 * hz * k / nz));
  };
  for (int i = 0; i < nx; ++i) {
    for (int k = 0; k < nz; ++k) {
      // Counter-clockwise seen from above (+y): the face normal points up.
      mesh->addTriangle(vertex(i, k), vertex(i, k + 1), vertex(i + 1, k + 1));
      mesh->addTriangle(vertex(i, k), vertex(i + 1, k + 1), vertex(i + 1, k));
    }
  }
  return mesh;
}

}  // namespace

RestingRopeScene::RestingRopeScene(const RestingRopeSceneSettings& settings)
    : WorldScene("rest", settings.timeStep), settings_(settings) {
  validate(settings);
  const double halfWidth = 0.5 * settings.spacing * (settings.ropeCount - 1);
  const double hx = 0.5 * settings.ropeLength + 0.5;  // the surface reaches 0.5 m past the rope ends
  const double hz = halfWidth + 0.5;
  switch (settings.surface) {
    case Settings::Surface::kPlane:
      physics_.addGround(0.0);
      break;
    case Settings::Surface::kBox:
      physics_.addBox(btVector3(static_cast<btScalar>(hx), btScalar(0.1), static_cast<btScalar>(hz)), 0.0,
                      btVector3(0, btScalar(-0.1), 0));
      break;
    case Settings::Surface::kTriangleMesh: {
      btTransform identity;
      identity.setIdentity();
      physics_.addStaticMesh(flatGrid(hx, hz, 0.1), identity);
      break;
    }
  }
  RodSettings rod = settings.rod;
  rod.restLength = settings.ropeLength;
  const double y = rod.radius + settings.gap;
  const double half = 0.5 * settings.ropeLength;
  for (int i = 0; i < settings.ropeCount; ++i) {
    // Off the grid lines of the mesh by 1.3 cm so that the ropes cross triangle diagonals.
    const double z = -halfWidth + settings.spacing * i + 0.013;
    ropes_.push_back(std::make_unique<bullet::RopeObject>(
        Rod::fromSegment(rod, Vec3(-half, y, z), Vec3(half, y, z)), settings.bridge));
    physics_.ropes().addRope(*ropes_.back());
  }
}

RestingRopeScene::~RestingRopeScene() = default;

int RestingRopeScene::maxControlPoints() const {
  int most = 0;
  for (const auto& rope : ropes_) most = std::max(most, rope->rod().controlPointCount());
  return most;
}

double RestingRopeScene::maxSpeed() const {
  double fastest = 0.0;
  for (const auto& rope : ropes_) {
    for (const Vec3& v : rope->rod().velocities()) fastest = std::max(fastest, v.norm());
  }
  return fastest;
}

double RestingRopeScene::lowestPoint() const {
  constexpr int kSamples = 200;
  double lowest = ropes_.front()->rod().position(ropes_.front()->rod().beginParameter()).y();
  for (const auto& rope : ropes_) {
    const Rod& rod = rope->rod();
    for (int i = 0; i <= kSamples; ++i) {
      const double s = rod.beginParameter() + (rod.endParameter() - rod.beginParameter()) * i / kSamples;
      lowest = std::min(lowest, rod.position(std::min(s, rod.endParameter())).y());
    }
  }
  return lowest;
}

StepMeasurements RestingRopeScene::step() { return advance(); }

StepMeasurements RestingRopeScene::measure() const {
  StepMeasurements total;
  total.maxPenetration = 0.0;
  total.maxSelfOverlap = 0.0;
  int contacts = 0;
  for (const auto& rope : ropes_) {
    const StepMeasurements one = ropeMeasurements(physics_, *rope);
    total.controlPoints += one.controlPoints;
    total.maxStrain = std::max(total.maxStrain, one.maxStrain);
    total.maxPenetration = std::max(*total.maxPenetration, one.maxPenetration.value_or(0.0));
    total.maxSelfOverlap = std::max(*total.maxSelfOverlap, one.maxSelfOverlap.value_or(0.0));
    contacts += rope->lastStep().contacts;
  }
  total.series = {{"contacts", static_cast<double>(contacts)}, {"max_speed_m_s", maxSpeed()}};
  return total;
}

void RestingRopeScene::draw(render::Scene& scene) const {
  physics_.draw(scene);
  for (const auto& rope : ropes_) drawRope(scene, *rope, true);
}

std::optional<render::Camera> RestingRopeScene::camera() const {
  render::Camera camera;
  camera.target = Vec3(0.0, 0.0, 0.0);
  camera.eye = Vec3(0.3, 0.6, 1.2 + settings_.spacing * settings_.ropeCount);
  return camera;
}

}  // namespace rope::demos
