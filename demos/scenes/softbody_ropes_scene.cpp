// SPDX-License-Identifier: MIT
#include "demos/scenes/softbody_ropes_scene.h"

#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>

#include <algorithm>
#include <string>

#include "rope/common/error.h"

namespace rope::demos {

namespace {

void validate(const SoftBodyRopesSceneSettings& settings) {
  if (settings.ropeCount < 1) throw InvalidArgument("settings.ropeCount", std::to_string(settings.ropeCount), "must be >= 1");
  requirePositive("settings.ropeLength", settings.ropeLength);
  requirePositive("settings.radius", settings.radius);
  requirePositive("settings.spacing", settings.spacing);
  if (settings.spacing <= 2.0 * settings.radius) {
    throw InvalidArgument("settings.spacing", formatValue(settings.spacing), "must exceed the rope's diameter");
  }
  requirePositive("settings.linearDensity", settings.linearDensity);
  if (settings.segments < 2) throw InvalidArgument("settings.segments", std::to_string(settings.segments), "must be >= 2");
  if (settings.iterations < 1) {
    throw InvalidArgument("settings.iterations", std::to_string(settings.iterations), "must be >= 1");
  }
  requireNonNegative("settings.friction", settings.friction);
  if (settings.friction > 1.0) throw InvalidArgument("settings.friction", formatValue(settings.friction), "must be <= 1");
  requirePositive("settings.timeStep", settings.timeStep);
}

}  // namespace

SoftBodyRopesScene::SoftBodyRopesScene(const SoftBodyRopesSceneSettings& settings) : settings_(settings) {
  validate(settings);
  configuration_ = std::make_unique<btSoftBodyRigidBodyCollisionConfiguration>();
  dispatcher_ = std::make_unique<btCollisionDispatcher>(configuration_.get());
  broadphase_ = std::make_unique<btDbvtBroadphase>();
  solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
  world_ = std::make_unique<btSoftRigidDynamicsWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(),
                                                      configuration_.get());
  world_->setGravity(btVector3(0, btScalar(-9.81), 0));
  btSoftBodyWorldInfo& info = world_->getWorldInfo();
  info.m_gravity = world_->getGravity();
  info.m_broadphase = broadphase_.get();
  info.m_dispatcher = dispatcher_.get();
  info.air_density = 0;
  info.m_sparsesdf.Initialize();

  // The same box as RestingRopeScene's kBox: top face y = 0, 0.5 m beyond the ropes on every side.
  const double halfWidth = 0.5 * settings.spacing * (settings.ropeCount - 1);
  boxShape_ = std::make_unique<btBoxShape>(btVector3(static_cast<btScalar>(0.5 * settings.ropeLength + 0.5),
                                                     btScalar(0.1), static_cast<btScalar>(halfWidth + 0.5)));
  btRigidBody::btRigidBodyConstructionInfo boxInfo(0, nullptr, boxShape_.get());
  boxInfo.m_startWorldTransform.setIdentity();
  boxInfo.m_startWorldTransform.setOrigin(btVector3(0, btScalar(-0.1), 0));
  boxInfo.m_friction = btScalar(0.5);
  box_ = std::make_unique<btRigidBody>(boxInfo);
  world_->addRigidBody(box_.get());

  const double half = 0.5 * settings.ropeLength;
  const double nodeMass = settings.linearDensity * settings.ropeLength / settings.segments;
  for (int i = 0; i < settings.ropeCount; ++i) {
    const btScalar z = static_cast<btScalar>(-halfWidth + settings.spacing * i + 0.013);
    const btScalar y = static_cast<btScalar>(settings.radius);
    // CreateRope(from, to, res, fixeds): res nodes between the two ends, so segments links; no pinned end.
    ropes_.emplace_back(btSoftBodyHelpers::CreateRope(info, btVector3(static_cast<btScalar>(-half), y, z),
                                                      btVector3(static_cast<btScalar>(half), y, z), settings.segments - 1, 0));
    btSoftBody& rope = *ropes_.back();
    for (int k = 0; k < rope.m_nodes.size(); ++k) {
      const bool end = k == 0 || k == rope.m_nodes.size() - 1;
      rope.setMass(k, static_cast<btScalar>(nodeMass * (end ? 0.5 : 1.0)));
    }
    rope.m_cfg.piterations = settings.iterations;
    rope.m_materials[0]->m_kLST = btScalar(1);
    rope.m_cfg.kDF = static_cast<btScalar>(settings.friction);
    rope.getCollisionShape()->setMargin(static_cast<btScalar>(settings.radius));
    world_->addSoftBody(&rope);
  }
}

SoftBodyRopesScene::~SoftBodyRopesScene() {
  for (auto& rope : ropes_) world_->removeSoftBody(rope.get());
  world_->removeRigidBody(box_.get());
}

void SoftBodyRopesScene::step() {
  const btScalar h = static_cast<btScalar>(settings_.timeStep);
  world_->stepSimulation(h, 1, h);
}

double SoftBodyRopesScene::lowestNode() const {
  double lowest = static_cast<double>(ropes_.front()->m_nodes[0].m_x.y());
  for (const auto& rope : ropes_) {
    for (int k = 0; k < rope->m_nodes.size(); ++k) lowest = std::min(lowest, static_cast<double>(rope->m_nodes[k].m_x.y()));
  }
  return lowest;
}

double SoftBodyRopesScene::maxSpeed() const {
  double fastest = 0.0;
  for (const auto& rope : ropes_) {
    for (int k = 0; k < rope->m_nodes.size(); ++k) {
      fastest = std::max(fastest, static_cast<double>(rope->m_nodes[k].m_v.length()));
    }
  }
  return fastest;
}

}  // namespace rope::demos
