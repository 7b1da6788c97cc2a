// SPDX-License-Identifier: MIT
#include "bullet_bridge/find_contacts.h"

#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btConcaveShape.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>

#include <cmath>
#include <string>

#include "bullet_bridge/kinematic_rope.h"
#include "bullet_bridge/narrowphase/concave_contact.h"
#include "bullet_bridge/narrowphase/convex_contact.h"
#include "bullet_bridge/narrowphase/convex_support.h"
#include "rope/common/error.h"

namespace rope::bullet {

namespace {

std::string shapeTypeName(const btCollisionShape& shape) {
  const char* name = shape.getName();
  return std::string(name != nullptr ? name : "unnamed") + " (shape type " +
         std::to_string(shape.getShapeType()) + ")";
}

// Throws for the first unsupported shape in the tree, before any contact is computed, so that a
// failing call leaves `out` unchanged.
void requireSupported(const btCollisionShape& shape) {
  if (shape.getShapeType() == COMPOUND_SHAPE_PROXYTYPE) {
    const auto& compound = static_cast<const btCompoundShape&>(shape);
    for (int i = 0; i < compound.getNumChildShapes(); ++i) {
      requireSupported(*compound.getChildShape(i));
    }
    return;
  }
  // A signed-distance-field shape reports no triangles, so it would silently never collide.
  if (shape.isConcave() && shape.getShapeType() != SDF_SHAPE_PROXYTYPE) return;
  ConvexCore core;
  if (!makeConvexCore(shape, core)) {
    throw InvalidArgument("object.shape", shapeTypeName(shape),
                          "unsupported collision shape for rope contacts");
  }
}

void appendContacts(const Capsule& capsule, const btCollisionShape& shape,
                    const btTransform& shapeToWorld, btScalar margin, int childIndex,
                    std::vector<Contact>& out) {
  const std::size_t first = out.size();
  if (shape.getShapeType() == COMPOUND_SHAPE_PROXYTYPE) {
    const auto& compound = static_cast<const btCompoundShape&>(shape);
    for (int i = 0; i < compound.getNumChildShapes(); ++i) {
      appendContacts(capsule, *compound.getChildShape(i),
                     shapeToWorld * compound.getChildTransform(i), margin,
                     childIndex < 0 ? i : childIndex, out);
    }
    return;
  }
  if (shape.getShapeType() == STATIC_PLANE_PROXYTYPE) {
    planeContacts(capsule, static_cast<const btStaticPlaneShape&>(shape), shapeToWorld, margin,
                  out);
  } else if (shape.isConcave()) {
    triangleMeshContacts(capsule, static_cast<const btConcaveShape&>(shape), shapeToWorld, margin,
                         out);
  } else {
    ConvexCore core;
    makeConvexCore(shape, core);  // supported: checked by requireSupported
    Contact contact;
    if (convexContact(capsule, core, shapeToWorld, margin, contact)) out.push_back(contact);
  }
  for (std::size_t i = first; i < out.size(); ++i) out[i].childIndex = childIndex;
}

// A kinematic rope's capsule is a segment core rounded by the radius, as a btCapsuleShape is
// (narrowphase/convex_support.h), through the same capsule-convex contact.
void kinematicCapsuleContact(const Capsule& capsule, const Capsule& other, btScalar margin, std::vector<Contact>& out) {
  const btVector3 axis = other.b - other.a;
  ConvexCore core;
  core.kind = ConvexCore::Kind::Segment;
  core.upAxis = 1;
  core.halfHeight = axis.length() / 2;
  core.rounding = other.radius;
  core.size = core.halfHeight;
  btTransform coreToWorld(btQuaternion::getIdentity(), (other.a + other.b) * btScalar(0.5));
  if (core.halfHeight > 0) coreToWorld.setRotation(shortestArcQuat(btVector3(0, 1, 0), axis / axis.length()));
  Contact contact;
  if (convexContact(capsule, core, coreToWorld, margin, contact)) out.push_back(contact);
}

}  // namespace

void findContacts(const Capsule& capsule, const btCollisionObject& object, double margin,
                  std::vector<Contact>& out) {
  requireValidCapsule("capsule", capsule);
  if (!(std::isfinite(margin) && margin >= 0)) requireNonNegative("margin", margin);
  const btCollisionShape* shape = object.getCollisionShape();
  if (shape == nullptr) {
    throw InvalidArgument("object.shape", "null", "the collision object has no shape");
  }
  if (const KinematicRope* rope = KinematicRope::ropeOf(object)) {
    // Its capsules near this one (a box test: the chain is short next to the cost of a contact), in
    // capsule order; childIndex = the capsule, as for any compound.
    const btScalar reach = capsule.radius + static_cast<btScalar>(margin + rope->settings().radius);
    btVector3 lo = capsule.a, hi = capsule.a;
    lo.setMin(capsule.b);
    hi.setMax(capsule.b);
    lo -= btVector3(reach, reach, reach);
    hi += btVector3(reach, reach, reach);
    for (int i = 0; i < rope->capsuleCount(); ++i) {
      const Capsule other = rope->capsule(i);
      btVector3 otherLo = other.a, otherHi = other.a;
      otherLo.setMin(other.b);
      otherHi.setMax(other.b);
      if (!TestAabbAgainstAabb2(lo, hi, otherLo, otherHi)) continue;
      const std::size_t first = out.size();
      kinematicCapsuleContact(capsule, other, btScalar(margin), out);
      for (std::size_t c = first; c < out.size(); ++c) out[c].childIndex = i;
    }
    return;
  }
  requireSupported(*shape);
  appendContacts(capsule, *shape, object.getWorldTransform(), btScalar(margin), -1, out);
}

}  // namespace rope::bullet
