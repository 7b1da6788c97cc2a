// SPDX-License-Identifier: MIT
#include "demos/scenes/physics_world.h"

#include "bullet_bridge/capsule_proxies.h"
#include "bullet_bridge/kinematic_rope.h"

#include <stdexcept>
#include "render/rope_drawing.h"
#include "render/world_extraction.h"

namespace rope::demos {

PhysicsWorld::PhysicsWorld(const btVector3& gravity)
    : bullet_(std::make_unique<BulletWorld>(gravity)), ropes_(std::make_unique<bullet::RopeWorld>(bullet_->world)) {}

PhysicsWorld::~PhysicsWorld() {
  ropes_.reset();  // takes its action and any remaining rope capsules out of the world
  for (auto& body : bodies_) bullet_->world.removeRigidBody(body.get());
}

btRigidBody* PhysicsWorld::addBox(const btVector3& halfExtents, double mass, const btTransform& transform) {
  return addBody(std::make_unique<btBoxShape>(halfExtents), mass, transform);
}

btRigidBody* PhysicsWorld::addBody(std::unique_ptr<btCollisionShape> shape, double mass, const btTransform& transform) {
  shapes_.push_back(std::move(shape));
  btCollisionShape* added = shapes_.back().get();
  btVector3 inertia(0, 0, 0);
  if (mass > 0) added->calculateLocalInertia(static_cast<btScalar>(mass), inertia);
  btRigidBody::btRigidBodyConstructionInfo info(static_cast<btScalar>(mass), nullptr, added, inertia);
  info.m_startWorldTransform = transform;
  info.m_friction = btScalar(0.5);
  bodies_.push_back(std::make_unique<btRigidBody>(info));
  bullet_->world.addRigidBody(bodies_.back().get());
  return bodies_.back().get();
}

btRigidBody* PhysicsWorld::addStaticMesh(std::unique_ptr<btTriangleMesh> mesh, const btTransform& transform) {
  triangleMeshes_.push_back(std::move(mesh));
  return addBody(std::make_unique<btBvhTriangleMeshShape>(triangleMeshes_.back().get(), true), 0.0, transform);
}

btRigidBody* PhysicsWorld::addBox(const btVector3& halfExtents, double mass, const btVector3& origin) {
  btTransform transform;
  transform.setIdentity();
  transform.setOrigin(origin);
  return addBox(halfExtents, mass, transform);
}

btRigidBody* PhysicsWorld::addGround(double height) {
  shapes_.push_back(std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), static_cast<btScalar>(height)));
  btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, shapes_.back().get());
  info.m_friction = btScalar(0.5);
  bodies_.push_back(std::make_unique<btRigidBody>(info));
  bullet_->world.addRigidBody(bodies_.back().get());
  return bodies_.back().get();
}

void PhysicsWorld::draw(render::Scene& scene) const {
  render::ExtractionOptions options;
  options.skip = [](const btCollisionObject& object) {
    return bullet::CapsuleProxies::ropeOf(object) != nullptr || bullet::KinematicRope::ropeOf(object) != nullptr;
  };
  render::extractWorld(bullet_->world, meshes_, scene, options);
}

StepMeasurements stepAndCheck(PhysicsWorld& physics, double h, const std::string& scene) {
  physics.world().stepSimulation(static_cast<btScalar>(h), 1, static_cast<btScalar>(h));
  const bullet::ContactReport& report = physics.ropes().lastReport();
  StepMeasurements counts;
  for (const bullet::RopeStepRecord& rope : report.ropes) {
    if (!rope.ok) throw std::runtime_error(scene + ": rope step failed: " + rope.failure);
    counts.insertions += rope.insertions;
    counts.removals += rope.removals;
  }
  if (*report.ropeContactFailure != '\0') throw std::runtime_error(scene + ": " + report.ropeContactFailure);
  return counts;
}

StepMeasurements ropeMeasurements(const PhysicsWorld& physics, const bullet::RopeObject& rope) {
  StepMeasurements measurements;
  measurements.controlPoints = rope.rod().controlPointCount();
  measurements.maxStrain = rope.rod().maxStrain();
  measurements.maxPenetration = rope.lastStep().maxPenetration;
  measurements.maxSelfOverlap = physics.ropes().lastReport().maxSelfOverlap();
  return measurements;
}

void drawRope(render::Scene& scene, const bullet::RopeObject& rope, bool showControlPolygon) {
  render::RopeStyle style;
  style.tube.radius = rope.rod().settings().radius;
  style.tube.alternateSpanColours = true;
  style.showControlPolygon = showControlPolygon;
  style.controlPolygon.lineRadius = 0.2 * style.tube.radius;
  style.controlPolygon.pointRadius = 0.45 * style.tube.radius;
  render::addRope(scene, rope.rod().knots(), rope.rod().controlPoints(), style);
}

}  // namespace rope::demos
