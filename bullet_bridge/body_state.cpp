#include "bullet_bridge/body_state.h"

#include <cmath>

namespace rope::bullet {

namespace {

bool finite(const btVector3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

}  // namespace

bool bodyStateFinite(const btRigidBody& body) {
  const btTransform& transform = body.getCenterOfMassTransform();
  const btMatrix3x3& basis = transform.getBasis();
  return finite(transform.getOrigin()) && finite(basis[0]) && finite(basis[1]) && finite(basis[2]) &&
         finite(body.getLinearVelocity()) && finite(body.getAngularVelocity()) && std::isfinite(body.getInvMass()) &&
         finite(body.getInvInertiaDiagLocal());
}

}  // namespace rope::bullet
