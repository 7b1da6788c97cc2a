// SPDX-License-Identifier: MIT
#include "bullet_bridge/detail/body_state.h"

#include <BulletCollision/BroadphaseCollision/btBroadphaseProxy.h>

#include <cmath>

#include "bullet_bridge/detail/bullet_math.h"
#include "bullet_bridge/kinematic_rope.h"

namespace rope::bullet {

bool bodyStateFinite(const btRigidBody& body) {
  const btTransform& transform = body.getCenterOfMassTransform();
  const btMatrix3x3& basis = transform.getBasis();
  return isFinite(transform.getOrigin()) && isFinite(basis[0]) && isFinite(basis[1]) && isFinite(basis[2]) &&
         isFinite(body.getLinearVelocity()) && isFinite(body.getAngularVelocity()) && std::isfinite(body.getInvMass()) &&
         isFinite(body.getInvInertiaDiagLocal()) && isFinite(body.getTotalForce()) && isFinite(body.getTotalTorque());
}

btRigidBody* dynamicBody(const btCollisionObject& object) {
  btRigidBody* body = btRigidBody::upcast(const_cast<btCollisionObject*>(&object));
  if (body == nullptr || body->isStaticOrKinematicObject() || !(body->getInvMass() > 0)) return nullptr;
  return body;
}

Vec3 pointVelocity(const btCollisionObject& object, const btVector3& point, int childIndex) {
  if (const KinematicRope* rope = KinematicRope::ropeOf(object)) {
    return childIndex >= 0 && childIndex < rope->capsuleCount() ? toVec(rope->surfaceVelocity(childIndex, point))
                                                                : Vec3::Zero();
  }
  const btRigidBody* body = btRigidBody::upcast(&object);
  if (body == nullptr) return Vec3::Zero();
  return toVec(body->getVelocityInLocalPoint(point - body->getCenterOfMassPosition()));
}

Vec3 pointAccelerationFromForces(const btRigidBody& body, const btVector3& arm) {
  const btVector3 angular = body.getInvInertiaTensorWorld() * body.getTotalTorque();
  return toVec(body.getTotalForce() * body.getInvMass() + angular.cross(arm));
}

double sweptReach(const btCollisionObject& object, double h) {
  const btRigidBody* rigid = btRigidBody::upcast(&object);
  const btBroadphaseProxy* handle = object.getBroadphaseHandle();
  if (rigid == nullptr || handle == nullptr) return 0.0;
  const double spin = static_cast<double>(rigid->getAngularVelocity().length());
  const double extent = 0.5 * static_cast<double>((handle->m_aabbMax - handle->m_aabbMin).length());
  return h * (static_cast<double>(rigid->getLinearVelocity().length()) + spin * extent);
}

Eigen::Matrix3d pointInverseMass(const btRigidBody& body, const btVector3& arm) {
  const btMatrix3x3& inverseInertia = body.getInvInertiaTensorWorld();
  Eigen::Matrix3d inertiaInverse;
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) inertiaInverse(row, col) = static_cast<double>(inverseInertia[row][col]);
  const Vec3 r = toVec(arm);
  Eigen::Matrix3d cross;
  cross << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  const Eigen::Matrix3d w =
      static_cast<double>(body.getInvMass()) * Eigen::Matrix3d::Identity() - cross * inertiaInverse * cross;
  return 0.5 * (w + w.transpose());
}

}  // namespace rope::bullet
