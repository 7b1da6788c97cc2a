// SPDX-License-Identifier: MIT
#include "demos/scenes/knot_scene.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/primitive_mesh.h"
#include "rope/common/error.h"
#include "rope/spline/arc_length.h"

namespace rope::demos {

// Coulomb coefficient of every contact of the knot scene (rope-rope and rope-body).
constexpr double kKnotFriction = 0.3;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kTrefoilPoints = 64;  // polyline points on the knotted part (one control point each)
constexpr int kTailPoints = 6;      // per tail
constexpr double kGripperHalf[3] = {0.02, 0.02, 0.01};  // m, thin along the pull (z)
constexpr double kGripperGap = 0.003;                  // m between the rope's end cap and the gripper

// The trefoil (sin t + 2 sin 2t, -(cos t - 2 cos 2t), -sin 3t) R: its top lobe at t = pi is where it is
// cut open; y is flipped so that the knot hangs below the tails.
Vec3 trefoil(double t, double scale) {
  return scale * Vec3(std::sin(t) + 2.0 * std::sin(2.0 * t), -(std::cos(t) - 2.0 * std::cos(2.0 * t)), -std::sin(3.0 * t));
}

void validate(const KnotSceneSettings& settings) {
  requirePositive("settings.loopScale", settings.loopScale);
  requirePositive("settings.endGap", settings.endGap);
  if (!(settings.endGap < 1.0)) throw InvalidArgument("settings.endGap", formatValue(settings.endGap), "must be < 1 rad");
  requirePositive("settings.tailLength", settings.tailLength);
  requirePositive("settings.height", settings.height);
  requireNonNegative("settings.settleTime", settings.settleTime);
  requirePositive("settings.pullSpeed", settings.pullSpeed);
  requirePositive("settings.pullTension", settings.pullTension);
  requirePositive("settings.timeStep", settings.timeStep);
  settings.rod.validate();
  settings.bridge.validate();
}

}  // namespace

RodSettings KnotSceneSettings::defaultRod() {
  RodSettings rod;
  rod.radius = 0.005;
  rod.youngsModulus = 1.0e8;      // EA = 7.85 kN
  rod.bendingStiffness = 1.0e-4;  // N m^2: a limp cord that bends around its own diameter
  // Damping: the default material (Kelvin–Voigt) damping, 1 ms. Undamped, the knot overshoots the
  // grippers' 3 N pull (held tension 3.45 N, overlap 1.94 mm, 0.198 m of rope in the knot instead of
  // 0.218 m); the mass and stiffness damping (0.5 /s, 1 ms) the scene set before did the same job and
  // also dragged the rope's rigid motion and swing (measured 2026-11-29).
  rod.maxControlPoints = 160;
  return rod;
}

bullet::BulletRopeSettings KnotSceneSettings::defaultBridge() {
  bullet::BulletRopeSettings bridge;
  // Rope-rope friction 0.3, the value the knot was tuned with: Bullet's combined friction is the
  // product of the two coefficients (friction_combination.h), so each strand carries sqrt(0.3); the
  // ground and the grippers get the same coefficient (KnotScene), so rope-body friction is 0.3 too.
  bridge.friction = std::sqrt(kKnotFriction);
  // Everything else is the library's default, the speculative margin (1 cm) included: a 2.5 mm margin
  // gave the knot the same motion bit for bit at 0.80x the cost per step and the pile a deeper impact
  // into the ground (2.8 mm against 2.0 mm) at 0.93x.
  return bridge;
}

KnotSceneSettings KnotSceneSettings::gravity() {
  KnotSceneSettings settings;
  settings.tightening = Tightening::kGravity;
  // A heavy cord (0.3 kg/m, a wet rope or a light chain): its own weight, hanging from the knot between
  // the fixed grippers, is what draws the knot tight. At 0.09 kg/m the same knot stops at about twice
  // the length (measured: 0.22 m of rope in the knot instead of 0.14 m).
  settings.rod.linearDensity = 0.3;
  return settings;
}

PointList overhandKnotPolyline(const KnotSceneSettings& settings) {
  validate(settings);
  const double R = settings.loopScale;
  const double t0 = kPi + settings.endGap;
  const double t1 = 3.0 * kPi - settings.endGap;
  const Vec3 offset(0.0, settings.height - trefoil(t0, R).y(), 0.0);  // the cut ends at the tails' height
  const Vec3 first = trefoil(t0, R) + offset;
  const Vec3 last = trefoil(t1, R) + offset;
  PointList points;
  for (int k = kTailPoints; k >= 1; --k) points.push_back(first - Vec3(0, 0, settings.tailLength * k / kTailPoints));
  for (int i = 0; i <= kTrefoilPoints; ++i) points.push_back(trefoil(t0 + (t1 - t0) * i / kTrefoilPoints, R) + offset);
  for (int k = 1; k <= kTailPoints; ++k) points.push_back(last + Vec3(0, 0, settings.tailLength * k / kTailPoints));
  return points;
}

KnotRegion knotRegion(const bullet::RopeObject& rope, const bullet::ContactReport& report) {
  KnotRegion region;
  for (const bullet::RopePairContactRecord& contact : report.ropeContacts) {
    if (!contact.active || contact.ropeA != &rope || contact.ropeB != &rope) continue;
    const double lo = std::min(contact.sA, contact.sB), hi = std::max(contact.sA, contact.sB);
    region.begin = region.found ? std::min(region.begin, lo) : lo;
    region.end = region.found ? std::max(region.end, hi) : hi;
    region.found = true;
  }
  if (!region.found) return region;
  const Rod& rod = rope.rod();
  // A read-out, every step: 8 Gauss points per knot span, not arcLength's default 16 on 4 pieces per
  // span, which cost 5 % of the knot scene's step for digits nothing reads (the 300 lengths a 10 s
  // `ropesim knot` run records agree to all 10 digits it prints).
  ArcLengthOptions quadrature;
  quadrature.gaussPoints = 8;
  quadrature.piecesPerSpan = 1;
  region.length = arcLength(rod.knots(), rod.controlPoints(), region.begin, region.end, quadrature);
  constexpr int kSamples = 200;
  std::vector<double> samples(kSamples + 1);
  samples[0] = region.begin;
  for (int i = 1; i <= kSamples; ++i) {
    samples[static_cast<size_t>(i)] = std::min(region.end, region.begin + (region.end - region.begin) * i / kSamples);
  }
  PointList points;
  rod.positionsAt(samples, points);  // ascending: one pass along the knot spans
  Vec3 lo = points[0], hi = lo;
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  region.extent = (hi - lo).maxCoeff();
  return region;
}

KnotScene::KnotScene(const KnotSceneSettings& settings) : WorldScene("knot", settings.timeStep), settings_(settings) {
  const PointList points = overhandKnotPolyline(settings);  // validates
  physics_.addGround(0.0)->setFriction(static_cast<btScalar>(std::sqrt(kKnotFriction)));
  RodSettings rod = settings.rod;
  rope_ = std::make_unique<bullet::RopeObject>(Rod::fromPolyline(rod, points, Rod::RestShape::kAsGiven),
                                               settings.bridge);
  physics_.ropes().addRope(*rope_);
  const double s[2] = {rope_->rod().beginParameter(), rope_->rod().endParameter()};
  const double direction[2] = {-1.0, 1.0};  // the tails lead out along -z and +z
  const btVector3 half(static_cast<btScalar>(kGripperHalf[0]), static_cast<btScalar>(kGripperHalf[1]),
                       static_cast<btScalar>(kGripperHalf[2]));
  for (int i = 0; i < 2; ++i) {
    pinPoints_[i] = toBullet(rope_->rod().position(s[i]));
    pins_[i] = rope_->attachToPoint(s[i], pinPoints_[i]);
    const btVector3 centre =
        pinPoints_[i] + btVector3(0, 0, static_cast<btScalar>(direction[i] * (kGripperHalf[2] + rod.radius + kGripperGap)));
    grippers_[i] = physics_.addBox(half, 0.0, centre);
    grippers_[i]->setFriction(static_cast<btScalar>(std::sqrt(kKnotFriction)));
    grippers_[i]->setCollisionFlags(grippers_[i]->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
    grippers_[i]->setActivationState(DISABLE_DEACTIVATION);
  }
}

double KnotScene::endStrain() const {
  const Rod& rod = rope_->rod();
  const double inset = 0.02;  // m of parameter: past the pin's own knot span
  return 0.5 * (rod.strain(rod.beginParameter() + inset) + rod.strain(rod.endParameter() - inset));
}

double KnotScene::endSeparation() const { return static_cast<double>((pinPoints_[1] - pinPoints_[0]).length()); }

void KnotScene::moveGrippers(double h) {
  if (settings_.tightening != KnotSceneSettings::Tightening::kPull || time() < settings_.settleTime) return;
  const Rod& rod = rope_->rod();
  const double targetStrain = settings_.pullTension / rod.settings().axialStiffness();
  const double s[2] = {rod.beginParameter() + 0.02, rod.endParameter() - 0.02};
  const double direction[2] = {-1.0, 1.0};
  for (int i = 0; i < 2; ++i) {
    // Proportional force control: full speed out while slack, easing in above the target tension.
    const double speed = settings_.pullSpeed * std::clamp(1.0 - rod.strain(s[i]) / targetStrain, -1.0, 1.0);
    const btVector3 move(0, 0, static_cast<btScalar>(direction[i] * speed * h));
    pinPoints_[i] += move;
    rope_->setAttachmentTarget(pins_[i], pinPoints_[i]);
    btTransform transform = grippers_[i]->getWorldTransform();
    transform.setOrigin(transform.getOrigin() + move);
    grippers_[i]->setWorldTransform(transform);  // Bullet derives the kinematic velocity from the move
  }
}

StepMeasurements KnotScene::step() {
  moveGrippers(settings_.timeStep);
  return advance();
}

StepMeasurements KnotScene::measure() const {
  const Rod& rod = rope_->rod();
  StepMeasurements measurements = ropeMeasurements(physics_, *rope_);
  const KnotRegion region = knot();
  measurements.series = {{"knot_length_m", region.length},
                         {"knot_extent_m", region.extent},
                         {"self_contacts", static_cast<double>(rope_->lastStep().ropeContacts)},
                         {"self_overlap_m", physics_.ropes().lastReport().maxSelfOverlap()},
                         {"end_separation_m", endSeparation()},
                         {"end_tension_n", endStrain() * rod.settings().axialStiffness()}};
  return measurements;
}

void KnotScene::draw(render::Scene& scene) const {
  physics_.draw(scene);
  drawRope(scene, *rope_, true);
}

std::optional<render::Camera> KnotScene::camera() const {
  render::Camera camera;
  // Follows the knot (the rope's middle: the slack sags 0.3 m before the pull lifts it again), close
  // enough that the tight knot, a few centimetres across, fills a good part of the frame.
  const Rod& rod = rope_->rod();
  camera.target = rod.position(0.5 * (rod.beginParameter() + rod.endParameter()));
  camera.eye = camera.target + Vec3(0.2, 0.06, 0.08);
  return camera;
}

}  // namespace rope::demos
