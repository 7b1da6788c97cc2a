// SPDX-License-Identifier: MIT
#include "bullet_bridge/body_state.h"

#include <cmath>

#include "bullet_bridge/bullet_math.h"

namespace rope::bullet {

bool bodyStateFinite(const btRigidBody& body) {
  const btTransform& transform = body.getCenterOfMassTransform();
  const btMatrix3x3& basis = transform.getBasis();
  return isFinite(transform.getOrigin()) && isFinite(basis[0]) && isFinite(basis[1]) && isFinite(basis[2]) &&
         isFinite(body.getLinearVelocity()) && isFinite(body.getAngularVelocity()) && std::isfinite(body.getInvMass()) &&
         isFinite(body.getInvInertiaDiagLocal());
}

btRigidBody* dynamicBody(const btCollisionObject& object) {
  btRigidBody* body = btRigidBody::upcast(const_cast<btCollisionObject*>(&object));
  if (body == nullptr || body->isStaticOrKinematicObject() || !(body->getInvMass() > 0)) return nullptr;
  return body;
}

Vec3 pointVelocity(const btCollisionObject& object, const btVector3& point) {
  const btRigidBody* body = btRigidBody::upcast(&object);
  if (body == nullptr) return Vec3::Zero();
  return toVec(body->getVelocityInLocalPoint(point - body->getCenterOfMassPosition()));
}

}  // namespace rope::bullet
