// SPDX-License-Identifier: MIT
#include "demos/scenes/scene_state.h"

#include "bullet_bridge/capsule_proxies.h"
#include "bullet_bridge/kinematic_rope.h"

namespace rope::demos {

namespace {

void appendPoints(const PointList& points, std::vector<double>& state) {
  for (const Vec3& p : points) state.insert(state.end(), {p.x(), p.y(), p.z()});
}

void appendKnots(const KnotVector& knots, std::vector<double>& state) {
  for (int i = 0; i < knots.size(); ++i) state.push_back(knots[i]);
}

void appendVector(const btVector3& v, std::vector<double>& state) {
  state.insert(state.end(), {static_cast<double>(v.x()), static_cast<double>(v.y()), static_cast<double>(v.z())});
}

}  // namespace

void appendRodState(const Rod& rod, std::vector<double>& state) {
  appendKnots(rod.knots(), state);
  appendPoints(rod.controlPoints(), state);
  appendPoints(rod.velocities(), state);
  appendPoints(rod.restControlPoints(), state);
  for (const Pin& pin : rod.pins()) {
    state.insert(state.end(), {pin.parameter, pin.target.x(), pin.target.y(), pin.target.z()});
  }
}

void appendTractrixState(const TractrixRope& rope, std::vector<double>& state) {
  appendKnots(rope.knots(), state);
  appendPoints(rope.controlPoints(), state);
}

void appendWorldState(const PhysicsWorld& physics, std::vector<double>& state) {
  const btCollisionObjectArray& objects = physics.world().getCollisionObjectArray();
  for (int i = 0; i < objects.size(); ++i) {
    const btCollisionObject& object = *objects[i];
    if (bullet::CapsuleProxies::ropeOf(object) != nullptr || bullet::KinematicRope::ropeOf(object) != nullptr) continue;
    const btTransform& transform = object.getWorldTransform();
    appendVector(transform.getOrigin(), state);
    for (int row = 0; row < 3; ++row) appendVector(transform.getBasis()[row], state);
    if (const btRigidBody* body = btRigidBody::upcast(&object)) {
      appendVector(body->getLinearVelocity(), state);
      appendVector(body->getAngularVelocity(), state);
    }
  }
  for (const bullet::RopeObject* rope : physics.ropes().ropes()) appendRodState(rope->rod(), state);
}

}  // namespace rope::demos
