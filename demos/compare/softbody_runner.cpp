// SPDX-License-Identifier: MIT
// Bullet soft-body side: btSoftBodyHelpers::CreateRope in a btSoftRigidDynamicsWorld. What matches
// and what cannot: length, mass (lumped at the nodes), gravity, time step and collision radius (the
// soft body's margin) match; the links are position-based constraints whose stiffness kLST in (0, 1]
// and iteration count set an effective compliance, not EA, so the axial stiffness cannot be set to
// the rope's (we sweep kLST and piterations instead); the rope has no bending stiffness; mass damping
// c is kDP = c h (Bullet scales the node velocity by 1 - kDP each step). Rigid contact is Bullet's
// default SDF_RS: nodes only (not links) against a sparse signed distance field of the rigid shape.

#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <vector>

#include "demos/compare/runners.h"
#include "demos/compare/scene_specs.h"
#include "rope/common/error.h"

namespace rope::compare::softbody {
namespace {

using Clock = std::chrono::steady_clock;

Eigen::Vector3d toEigen(const btVector3& v) {
  return {static_cast<double>(v.x()), static_cast<double>(v.y()), static_cast<double>(v.z())};
}

// A soft-rigid world with its rope; owns everything it creates.
class SoftWorld {
 public:
  SoftWorld() {
    dispatcher_ = std::make_unique<btCollisionDispatcher>(&configuration_);
    world_ = std::make_unique<btSoftRigidDynamicsWorld>(dispatcher_.get(), &broadphase_, &solver_, &configuration_);
    world_->setGravity(btVector3(0, btScalar(-9.81), 0));
    btSoftBodyWorldInfo& info = world_->getWorldInfo();
    info.m_gravity = world_->getGravity();
    info.m_broadphase = &broadphase_;
    info.m_dispatcher = dispatcher_.get();
    info.air_density = 0;  // no aerodynamics: kDG and kLF are zero anyway
    info.m_sparsesdf.Initialize();
  }
  ~SoftWorld() {
    if (rope_) world_->removeSoftBody(rope_.get());
    for (auto& body : bodies_) world_->removeRigidBody(body.get());
  }
  SoftWorld(const SoftWorld&) = delete;
  SoftWorld& operator=(const SoftWorld&) = delete;

  void addStaticBox(const Eigen::Vector3d& centre, const Eigen::Vector3d& half) {
    shapes_.push_back(std::make_unique<btBoxShape>(btVector3(btScalar(half.x()), btScalar(half.y()), btScalar(half.z()))));
    addStatic(btVector3(btScalar(centre.x()), btScalar(centre.y()), btScalar(centre.z())));
  }
  void addGround() {
    shapes_.push_back(std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), 0));
    addStatic(btVector3(0, 0, 0));
  }

  // A rope of `nodes` nodes from a to b; node masses lumped from the linear density; pinned ends
  // (bit 0: a, bit 1: b) get mass 0 (kinematic).
  btSoftBody& addRope(const Eigen::Vector3d& a, const Eigen::Vector3d& b, int nodes, int pinned, double linearDensity,
                      double radius, double massDamping, double h, const Setting& setting) {
    rope_.reset(btSoftBodyHelpers::CreateRope(world_->getWorldInfo(), btVector3(btScalar(a.x()), btScalar(a.y()), btScalar(a.z())),
                                              btVector3(btScalar(b.x()), btScalar(b.y()), btScalar(b.z())), nodes - 2, pinned));
    btSoftBody& rope = *rope_;
    const double segment = (b - a).norm() / (nodes - 1);
    for (int i = 0; i < nodes; ++i) {
      const bool end = i == 0 || i == nodes - 1;
      const bool fixed = (i == 0 && (pinned & 1)) || (i == nodes - 1 && (pinned & 2));
      rope.setMass(i, fixed ? 0 : btScalar(linearDensity * segment * (end ? 0.5 : 1.0)));
    }
    rope.m_cfg.piterations = setting.iterations;
    rope.m_materials[0]->m_kLST = btScalar(setting.stiffness);
    rope.m_cfg.kDP = btScalar(massDamping * h);
    rope.m_cfg.kDF = btScalar(0.5);  // friction, as PhysicsWorld's boxes
    rope.getCollisionShape()->setMargin(btScalar(radius));
    world_->addSoftBody(&rope);
    return rope;
  }

  btSoftRigidDynamicsWorld& world() { return *world_; }
  btSoftBody& rope() { return *rope_; }

  bool exploded() const {
    for (int i = 0; i < rope_->m_nodes.size(); ++i) {
      const btVector3& x = rope_->m_nodes[i].m_x;
      if (!std::isfinite(double(x.x())) || !std::isfinite(double(x.y())) || !std::isfinite(double(x.z())) ||
          x.length() > 1e3)
        return true;
    }
    return false;
  }
  double length() const {
    double length = 0;
    for (int i = 0; i < rope_->m_links.size(); ++i)
      length += double((rope_->m_links[i].m_n[0]->m_x - rope_->m_links[i].m_n[1]->m_x).length());
    return length;
  }
  // Points on the centre line: the nodes and `perLink` - 1 points inside each link.
  template <class F>
  void forEachPoint(int perLink, F f) const {
    for (int i = 0; i < rope_->m_links.size(); ++i) {
      const Eigen::Vector3d p = toEigen(rope_->m_links[i].m_n[0]->m_x), q = toEigen(rope_->m_links[i].m_n[1]->m_x);
      for (int k = 0; k <= perLink; ++k) f(p + (q - p) * (double(k) / perLink));
    }
  }

 private:
  void addStatic(const btVector3& origin) {
    btTransform transform;
    transform.setIdentity();
    transform.setOrigin(origin);
    btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, shapes_.back().get());
    info.m_startWorldTransform = transform;
    info.m_friction = btScalar(0.5);
    bodies_.push_back(std::make_unique<btRigidBody>(info));
    world_->addRigidBody(bodies_.back().get());
  }

  btSoftBodyRigidBodyCollisionConfiguration configuration_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  std::unique_ptr<btSoftRigidDynamicsWorld> world_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  std::unique_ptr<btSoftBody> rope_;
};

void validate(const Setting& setting) {
  if (setting.resolution < 3) throw InvalidArgument("setting.resolution", std::to_string(setting.resolution), "must be >= 3 nodes");
  if (setting.iterations < 1) throw InvalidArgument("setting.iterations", std::to_string(setting.iterations), "must be >= 1");
  if (!(setting.stiffness > 0 && setting.stiffness <= 1))
    throw InvalidArgument("setting.stiffness", formatValue(setting.stiffness), "must be in (0, 1]");
}

// Steps the world `duration` seconds at h, timing stepSimulation only; `before(t)` runs before each
// step (kinematic pins), `after(t)` after it, both outside the timer. Detects explosions.
template <class Before, class After>
void runWorld(SoftWorld& world, double h, double duration, const Limits& limits, Trial& trial, Before before, After after) {
  const int steps = static_cast<int>(std::lround(duration / h));
  for (int i = 1; i <= steps; ++i) {
    before(i * h);
    const auto start = Clock::now();
    world.world().stepSimulation(btScalar(h), 0, btScalar(h));
    trial.stepSeconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    trial.wallSeconds += trial.stepSeconds.back();
    trial.steps = i;
    trial.simulatedSeconds = i * h;
    if (world.exploded()) {
      trial.status = "exploded";
      return;
    }
    if (trial.wallSeconds > limits.wallBudget) {
      trial.status = "too slow";
      return;
    }
    after(i * h);
  }
}

void setNode(btSoftBody& rope, int i, const btVector3& x) {
  rope.m_nodes[i].m_x = x;
  rope.m_nodes[i].m_q = x;
  rope.m_nodes[i].m_v = btVector3(0, 0, 0);
}

Trial catenary(const Setting& setting, const Limits& limits, bool timePerStepOnly) {
  CatenarySpec spec;
  ScalingSpec scaling;
  const demos::HangSceneSettings& hang = spec.hang;
  RodSettings rod = hang.rod;
  rod.restLength = hang.ropeLength;
  const double h = hang.timeStep;
  const double half = 0.5 * hang.ropeLength;
  SoftWorld world;
  btSoftBody& rope = world.addRope({-half, hang.pinHeight, 0}, {half, hang.pinHeight, 0}, setting.resolution, 3,
                                   rod.effectiveLinearDensity(), rod.radius, rod.massDamping, h, setting);
  const int last = setting.resolution - 1;
  const double duration = limits.seconds > 0 ? limits.seconds : spec.seconds;
  Trial trial;
  double sagSum = 0;
  int samples = 0;
  Limits bounded = limits;
  if (timePerStepOnly) bounded.wallBudget = std::min(limits.wallBudget, scaling.wallBudget);
  runWorld(
      world, h, timePerStepOnly ? (scaling.warmupSteps + scaling.maxSteps) * h : duration, bounded, trial,
      [&](double t) {
        const btScalar x = btScalar(0.5 * spec.pinDistance(t));
        setNode(rope, 0, btVector3(-x, btScalar(hang.pinHeight), 0));
        setNode(rope, last, btVector3(x, btScalar(hang.pinHeight), 0));
      },
      [&](double t) {
        if (timePerStepOnly || t <= duration - spec.averagingWindow) return;
        double lowest = hang.pinHeight;
        for (int i = 0; i <= last; ++i) lowest = std::min(lowest, double(rope.m_nodes[i].m_x.y()));
        sagSum += hang.pinHeight - lowest;
        ++samples;
      });
  if (timePerStepOnly && trial.status == "too slow" && trial.steps >= 2) trial.status = "ok";
  trial.dofs = 3 * (setting.resolution - 2);
  if (samples > 0 && trial.ok()) {
    trial.metrics["sag_m"] = sagSum / samples;
    trial.metrics["sag_error"] = sagSum / samples / spec.analyticSag() - 1.0;
  }
  trial.metrics["strain"] = world.length() / hang.ropeLength - 1.0;
  return trial;
}

Trial heavyLoad(const Setting& setting, const Limits& limits) {
  HeavyLoadSpec spec;
  if (limits.loadMass > 0) spec.crane.boxMass = limits.loadMass;
  const demos::CraneSceneSettings& crane = spec.crane;
  RodSettings rod = crane.rod;
  rod.restLength = crane.ropeLength;
  const double h = crane.timeStep;
  SoftWorld world;
  world.addGround();
  // The 10 kg box is a point mass on the last node (friendlier to the soft body than an anchored box).
  btSoftBody& rope = world.addRope({0, crane.topHeight, 0}, {0, crane.topHeight - crane.ropeLength, 0}, setting.resolution,
                                   1, rod.effectiveLinearDensity(), rod.radius, rod.massDamping, h, setting);
  const int last = setting.resolution - 1;
  rope.setMass(last, rope.getMass(last) + btScalar(crane.boxMass));
  const double duration = limits.seconds > 0 ? limits.seconds : spec.seconds;
  Trial trial;
  double strainSum = 0;
  int samples = 0;
  runWorld(
      world, h, duration, limits, trial, [](double) {},
      [&](double t) {
        if (t <= duration - spec.averagingWindow) return;
        strainSum += world.length() / crane.ropeLength - 1.0;
        ++samples;
      });
  trial.dofs = 3 * (setting.resolution - 1);
  // Where the load ended up: a rope that cannot carry it stretches until the load lies on the ground.
  trial.metrics["load_height_m"] = double(rope.m_nodes[last].m_x.y());
  if (samples > 0 && trial.ok()) {
    trial.metrics["strain"] = strainSum / samples;
    trial.metrics["strain_error"] = strainSum / samples / spec.expectedStrain() - 1.0;
  }
  return trial;
}

Trial drape(const DrapeSpec& spec, const Setting& setting, const Limits& limits) {
  const demos::DrapeSceneSettings& drape = spec.drape;
  RodSettings rod = drape.rod;
  rod.restLength = drape.ropeLength;
  const double h = drape.timeStep;
  SoftWorld world;
  world.addGround();
  world.addStaticBox(spec.obstacleCentre(), spec.obstacleHalfExtents());
  const double y = drape.obstacleTop + drape.dropHeight + rod.radius;
  const double half = 0.5 * drape.ropeLength;
  world.addRope({-half, y, 0}, {half, y, 0}, setting.resolution, 0, rod.effectiveLinearDensity(), rod.radius,
                rod.massDamping, h, setting);
  const double duration = limits.seconds > 0 ? limits.seconds : spec.seconds;
  Trial trial;
  DrapePenetration penetration(spec, duration);
  runWorld(
      world, h, duration, limits, trial, [](double) {},
      [&](double t) { penetration.sample(t, [&](const auto& visit) { world.forEachPoint(4, visit); }); });
  double highest = -1e9;
  world.forEachPoint(1, [&](const Eigen::Vector3d& p) { highest = std::max(highest, p.y()); });
  trial.dofs = 3 * setting.resolution;
  penetration.record(trial.metrics);
  trial.metrics["highest_m"] = highest;
  return trial;
}

}  // namespace

Trial run(Scene scene, const Setting& setting, const Limits& limits) {
  validate(setting);
  switch (scene) {
    case Scene::kCatenary: return catenary(setting, limits, false);
    case Scene::kHeavyLoad: return heavyLoad(setting, limits);
    case Scene::kThinBar: return drape(DrapeSpec::thinBar(), setting, limits);
    case Scene::kDrape: return drape(DrapeSpec::box(), setting, limits);
    case Scene::kScaling: return catenary(setting, limits, true);
  }
  return Trial{};
}

}  // namespace rope::compare::softbody
