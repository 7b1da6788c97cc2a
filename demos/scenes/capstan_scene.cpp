// SPDX-License-Identifier: MIT
#include "demos/scenes/capstan_scene.h"

#include <algorithm>
#include <cmath>

#include "rope/common/error.h"

namespace rope::demos {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLoadGravity = 9.81;  // m/s^2: a load of F newtons is a body of F / 9.81 kg

using Settings = CapstanSceneSettings;

double obstacleRadius(const Settings& settings) {
  return settings.obstacle == Settings::Obstacle::kCylinder ? settings.cylinderRadius : settings.rod.radius;
}

void validate(const Settings& settings) {
  requirePositive("settings.wrapAngle", settings.wrapAngle);
  if (settings.wrapAngle > 4.0 * kPi) {
    throw InvalidArgument("settings.wrapAngle", formatValue(settings.wrapAngle), "must be <= 4 pi rad");
  }
  requireNonNegative("settings.friction", settings.friction);
  requirePositive("settings.loadRatio", settings.loadRatio);
  if (settings.loadRatio < 1.0) {
    throw InvalidArgument("settings.loadRatio", formatValue(settings.loadRatio), "must be >= 1 (heavy / light)");
  }
  requirePositive("settings.heavyLoad", settings.heavyLoad);
  requirePositive("settings.cylinderRadius", settings.cylinderRadius);
  requirePositive("settings.cylinderHalfLength", settings.cylinderHalfLength);
  requirePositive("settings.tautSpan", settings.tautSpan);
  requirePositive("settings.tautTension", settings.tautTension);
  if (!std::isfinite(settings.height)) throw InvalidArgument("settings.height", formatValue(settings.height), "must be finite");
  requirePositive("settings.strandLength", settings.strandLength);
  if (settings.helixPitch != Settings::kDerived) requireNonNegative("settings.helixPitch", settings.helixPitch);
  requireNonNegative("settings.loadRampTime", settings.loadRampTime);
  requirePositive("settings.timeStep", settings.timeStep);
  settings.rod.validate();
  settings.bridge.validate();
  if (settings.obstacle == Settings::Obstacle::kTautRope && settings.tautTension >= settings.rod.axialStiffness()) {
    throw InvalidArgument("settings.tautTension", formatValue(settings.tautTension),
                          "must be below the rope's EA (the taut rope's rest length would not be positive)");
  }
}

// Point of the wrap at angle phi from the top (towards +x), with the helix's advance along z.
Vec3 wrapPoint(const Settings& settings, double phi) {
  const double r = settings.wrapRadius();
  const double lead = settings.effectiveHelixPitch() / (2.0 * kPi);
  return Vec3(r * std::sin(phi), settings.height + r * std::cos(phi), lead * phi);
}

// Unit tangent of the wrap's circle in the x-y plane, in the direction of increasing phi.
Vec3 wrapTangent(double phi) { return Vec3(std::cos(phi), -std::sin(phi), 0.0); }

}  // namespace

RodSettings CapstanSceneSettings::defaultRod() {
  RodSettings rod;
  rod.radius = 0.005;
  rod.youngsModulus = 1.0e8;
  rod.bendingStiffness = 0.0;
  rod.gravity = Vec3::Zero();
  return rod;
}

double CapstanSceneSettings::effectiveHelixPitch() const {
  if (helixPitch != kDerived) return helixPitch;
  return wrapAngle > kPi ? 5.0 * rod.radius : 0.0;
}

double CapstanSceneSettings::wrapRadius() const { return obstacleRadius(*this) + rod.radius; }

double CapstanSceneSettings::capstanLimit() const { return std::exp(friction * wrapAngle); }

PointList capstanPolyline(const CapstanSceneSettings& settings) {
  validate(settings);
  const double r = settings.wrapRadius();
  const double half = 0.5 * settings.wrapAngle;
  // About 5 mm of arc between points (the rod's default minimum knot spacing), but no coarser than
  // 30 degrees and no finer than 5 degrees: the interpolating spline then stays on the circle to
  // well under a micrometre, far below any contact depth.
  const double step = std::clamp(0.005 / r, kPi / 36.0, kPi / 6.0);
  const int arcSegments = std::max(2, static_cast<int>(std::ceil(settings.wrapAngle / step)));
  const double spacing = r * settings.wrapAngle / arcSegments;
  // Strand points graded from the arc's spacing at the support, doubling outwards, so the
  // interpolation has no abrupt change of point spacing at the tangent point.
  std::vector<double> strand;
  for (double d = spacing; d < settings.strandLength; d *= 2.0) strand.push_back(d);
  if (!strand.empty() && settings.strandLength - strand.back() < 0.5 * strand.back()) strand.pop_back();
  strand.push_back(settings.strandLength);

  PointList points;
  const Vec3 begin = wrapPoint(settings, -half);
  const Vec3 beginOut = -wrapTangent(-half);
  for (auto d = strand.rbegin(); d != strand.rend(); ++d) points.push_back(begin + *d * beginOut);
  for (int k = 0; k <= arcSegments; ++k) {
    points.push_back(wrapPoint(settings, -half + settings.wrapAngle * k / arcSegments));
  }
  const Vec3 end = wrapPoint(settings, half);
  const Vec3 endOut = wrapTangent(half);
  for (double d : strand) points.push_back(end + d * endOut);
  return points;
}

CapstanScene::CapstanScene(const CapstanSceneSettings& settings) : WorldScene("capstan", settings.timeStep), settings_(settings) {
  const PointList points = capstanPolyline(settings);  // validates
  bullet::BulletRopeSettings bridge = settings.bridge;
  bridge.friction = settings.friction;
  // The law is for a weightless rope (RodSettings::gravity = 0) in a world whose gravity pulls the loads.
  bridge.gravitySource = bullet::BulletRopeSettings::GravitySource::kRod;

  const btScalar height = static_cast<btScalar>(settings.height);
  if (settings.obstacle == Settings::Obstacle::kCylinder) {
    const btScalar r = static_cast<btScalar>(settings.cylinderRadius);
    btTransform transform;
    transform.setIdentity();
    transform.setOrigin(btVector3(0, height, 0));
    // Friction 1: the contact's coefficient (the product, friction_combination.h) is the rope's mu.
    physics_.addBody(std::make_unique<btCylinderShapeZ>(
                         btVector3(r, r, static_cast<btScalar>(settings.cylinderHalfLength))),
                     0.0, transform)
        ->setFriction(btScalar(1.0));
  } else {
    // Stretched to tautTension between its two pinned ends: rest length span / (1 + T / EA).
    RodSettings taut = settings.rod;
    taut.restLength = settings.tautSpan / (1.0 + settings.tautTension / taut.axialStiffness());
    const double z = 0.5 * settings.tautSpan;
    // Friction 1 on the taut rope: the rope-rope coefficient (the product) is the wrapped rope's mu.
    bullet::BulletRopeSettings tautBridge = bridge;
    tautBridge.friction = 1.0;
    taut_ = std::make_unique<bullet::RopeObject>(
        Rod::fromSegment(taut, Vec3(0.0, settings.height, -z), Vec3(0.0, settings.height, z)), tautBridge);
    physics_.ropes().addRope(*taut_);
    taut_->attachToPoint(taut_->rod().beginParameter(), btVector3(0, height, static_cast<btScalar>(-z)));
    taut_->attachToPoint(taut_->rod().endParameter(), btVector3(0, height, static_cast<btScalar>(z)));
  }

  // The loads are added to the world before the rope, as a scene file adds its bodies before its ropes
  // (demos/scenes/capstan.json gives bitwise this scene's trajectory).
  Rod rod = Rod::fromPolyline(settings.rod, points, Rod::RestShape::kAsGiven);
  const double half = 0.5 * settings.wrapAngle;
  pullDirections_[0] = toBullet(-wrapTangent(-half));
  pullDirections_[1] = toBullet(wrapTangent(half));
  loadForces_[0] = settings.heavyLoad / settings.loadRatio;
  loadForces_[1] = settings.heavyLoad;
  const double sphereRadius = std::min(0.01, 0.4 * settings.wrapRadius());  // the two hanging loads never touch
  const double ends[2] = {rod.beginParameter(), rod.endParameter()};
  for (int i = 0; i < 2; ++i) {
    btTransform transform;
    transform.setIdentity();
    transform.setOrigin(toBullet(rod.position(ends[i])));
    loads_[i] = physics_.addBody(std::make_unique<btSphereShape>(static_cast<btScalar>(sphereRadius)),
                                 loadForces_[i] / kLoadGravity, transform);
    // Its own gravity along the strand (the ideal pulley), never put to sleep while it holds still.
    loads_[i]->setFlags(loads_[i]->getFlags() | BT_DISABLE_WORLD_GRAVITY);
    loads_[i]->setActivationState(DISABLE_DEACTIVATION);
    loadGravity_[i] = pullDirections_[i] * static_cast<btScalar>(kLoadGravity);
    startPositions_[i] = transform.getOrigin();
  }
  rope_ = std::make_unique<bullet::RopeObject>(std::move(rod), bridge);
  physics_.ropes().addRope(*rope_);
  for (int i = 0; i < 2; ++i) rope_->attachToBody(ends[i], *loads_[i], btVector3(0, 0, 0));
  applyLoads(0.0);
}

CapstanScene::~CapstanScene() = default;

void CapstanScene::applyLoads(double t) {
  const double ramp = settings_.loadRampTime > 0.0 ? std::min(1.0, t / settings_.loadRampTime) : 1.0;
  for (int i = 0; i < 2; ++i) {
    loads_[i]->setGravity(loadGravity_[i] * static_cast<btScalar>(ramp));
  }
}

StepMeasurements CapstanScene::step() {
  // The load of the coming step: the ramp's value at its end, so the full load is on from loadRampTime.
  const double next = static_cast<double>(++steps_) * settings_.timeStep;  // counted, not summed: no drift
  applyLoads(next);
  return advance(next);
}

double CapstanScene::heavyTravel() const {
  return static_cast<double>((loads_[1]->getCenterOfMassPosition() - startPositions_[1]).dot(pullDirections_[1]));
}

double CapstanScene::heavySpeed() const {
  return static_cast<double>(loads_[1]->getLinearVelocity().dot(pullDirections_[1]));
}

double CapstanScene::lightTravel() const {
  return static_cast<double>((loads_[0]->getCenterOfMassPosition() - startPositions_[0]).dot(pullDirections_[0]));
}

StepMeasurements CapstanScene::measure() const {
  StepMeasurements measurements = ropeMeasurements(physics_, *rope_);
  measurements.series = {{"heavy_travel_m", heavyTravel()},
                         {"heavy_speed_m_s", heavySpeed()},
                         {"contacts", static_cast<double>(rope_->lastStep().contacts)}};
  return measurements;
}

void CapstanScene::draw(render::Scene& scene) const {
  physics_.draw(scene);
  if (taut_) drawRope(scene, *taut_);
  drawRope(scene, *rope_, true);
}

std::optional<render::Camera> CapstanScene::camera() const {
  render::Camera camera;
  camera.target = Vec3(0.0, settings_.height - 0.1, 0.0);
  camera.eye = camera.target + Vec3(0.25, 0.15, 0.9);
  return camera;
}

}  // namespace rope::demos
