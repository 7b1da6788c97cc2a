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
#include "bullet_bridge/narrowphase/segment_segment_distance.h"
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

// The capsule against another capsule (a kinematic rope's): closest points of the two axes.
void capsuleContact(const Capsule& capsule, const Capsule& other, btScalar margin, std::vector<Contact>& out) {
  const SegmentPairClosest closest = segmentSegmentClosest(capsule.a, capsule.b, other.a, other.b);
  const btScalar distance = static_cast<btScalar>(closest.distance) - capsule.radius - other.radius;
  if (distance > margin) return;
  const btVector3 onAxis = capsule.a + (capsule.b - capsule.a) * static_cast<btScalar>(closest.s);
  const btVector3 onOther = other.a + (other.b - other.a) * static_cast<btScalar>(closest.t);
  btVector3 normal = onAxis - onOther;
  if (normal.length2() > btScalar(1e-24)) {
    normal.normalize();
  } else {
    // The axes meet: separate across both (or any direction normal to the capsule's).
    normal = (capsule.b - capsule.a).cross(other.b - other.a);
    if (normal.length2() < btScalar(1e-24)) {
      btVector3 unused;
      btPlaneSpace1(capsule.b - capsule.a, normal, unused);
    }
    normal.normalize();
  }
  Contact contact;
  contact.t = static_cast<btScalar>(closest.s);
  contact.normal = normal;
  contact.pointOnCapsule = onAxis - normal * capsule.radius;
  contact.pointOnBody = onOther + normal * other.radius;
  contact.distance = distance;
  out.push_back(contact);
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
    if (object.getUserIndex() >= 0 && object.getUserIndex() < rope->capsuleCount()) {
      capsuleContact(capsule, rope->capsule(object.getUserIndex()), btScalar(margin), out);
    }
    return;
  }
  requireSupported(*shape);
  appendContacts(capsule, *shape, object.getWorldTransform(), btScalar(margin), -1, out);
}

}  // namespace rope::bullet
