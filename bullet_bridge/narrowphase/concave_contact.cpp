// SPDX-License-Identifier: MIT
#include "bullet_bridge/narrowphase/concave_contact.h"

#include <BulletCollision/CollisionShapes/btTriangleCallback.h>

#include <algorithm>
#include <cmath>

#include "bullet_bridge/narrowphase/segment_triangle_distance.h"

namespace rope::bullet {

namespace {

Contact toWorld(const Contact& local, const btTransform& shapeToWorld) {
  Contact world = local;
  world.normal = shapeToWorld.getBasis() * local.normal;
  world.pointOnBody = shapeToWorld * local.pointOnBody;
  world.pointOnCapsule = shapeToWorld * local.pointOnCapsule;
  return world;
}

class TriangleCollector : public btTriangleCallback {
 public:
  TriangleCollector(const Capsule& localCapsule, const btTransform& shapeToWorld,
                    btScalar triangleMargin, btScalar margin, std::vector<Contact>& out)
      : capsule_(localCapsule),
        shapeToWorld_(shapeToWorld),
        triangleMargin_(triangleMargin),
        margin_(margin),
        out_(out) {}

  void processTriangle(btVector3* triangle, int partId, int triangleIndex) override {
    Contact contact;
    if (!triangleContact(capsule_, triangle[0], triangle[1], triangle[2], triangleMargin_, margin_,
                         contact)) {
      return;
    }
    contact.partIndex = partId;
    contact.triangleIndex = triangleIndex;
    out_.push_back(toWorld(contact, shapeToWorld_));
  }

 private:
  const Capsule& capsule_;
  const btTransform& shapeToWorld_;
  btScalar triangleMargin_;
  btScalar margin_;
  std::vector<Contact>& out_;
};

}  // namespace

void planeContacts(const Capsule& capsule, const btStaticPlaneShape& plane,
                   const btTransform& shapeToWorld, btScalar margin, std::vector<Contact>& out) {
  const btVector3 normal = shapeToWorld.getBasis() * plane.getPlaneNormal().normalized();
  const btVector3 origin = shapeToWorld * (plane.getPlaneNormal() * plane.getPlaneConstant());
  const bool pointAxis = capsule.a == capsule.b;
  for (int end = 0; end < (pointAxis ? 1 : 2); ++end) {
    const btVector3& centre = end == 0 ? capsule.a : capsule.b;
    const btScalar height = normal.dot(centre - origin);
    Contact contact;
    contact.distance = height - capsule.radius;
    if (contact.distance > margin) continue;
    contact.t = end;
    contact.normal = normal;
    contact.pointOnBody = centre - normal * height;
    contact.pointOnCapsule = centre - normal * capsule.radius;
    out.push_back(contact);
  }
}

bool triangleContact(const Capsule& capsule, const btVector3& a, const btVector3& b,
                     const btVector3& c, btScalar triangleMargin, btScalar margin,
                     Contact& contact) {
  const btScalar reach = capsule.radius + triangleMargin;
  const SegmentTriangleClosest closest = segmentTriangleClosest(capsule.a, capsule.b, a, b, c);
  if (closest.distance - reach > margin) return false;

  const btVector3 faceNormal = (b - a).cross(c - a);
  const btScalar faceLength = faceNormal.length();
  Contact local;
  if (closest.distance > 0) {
    local.normal = (closest.pointOnSegment - closest.pointOnTriangle) / closest.distance;
    local.distance = closest.distance - reach;
    local.t = closest.s;
    local.pointOnBody = closest.pointOnTriangle + local.normal * triangleMargin;
    local.pointOnCapsule = closest.pointOnSegment - local.normal * capsule.radius;
  } else if (faceLength > 0) {
    // The axis touches or crosses the triangle: resolve along the face normal, towards the side
    // of the endpoint farther from the plane (crossing) or either side (touching).
    const btVector3 n = faceNormal / faceLength;
    const btScalar ha = n.dot(capsule.a - a);
    const btScalar hb = n.dot(capsule.b - a);
    const bool aIsFar = std::fabs(ha) >= std::fabs(hb);
    const btScalar farHeight = aIsFar ? ha : hb;
    const btScalar nearHeight = aIsFar ? hb : ha;
    local.normal = farHeight < 0 ? -n : n;
    // Depth of the near endpoint behind the plane, along the chosen normal (>= 0 when crossing).
    const btScalar behind = std::max(btScalar(0), -local.normal.dot(n) * nearHeight);
    const btVector3& nearEnd = aIsFar ? capsule.b : capsule.a;
    const bool crossing = closest.crossesPlane;
    const btVector3 anchor = crossing ? nearEnd : closest.pointOnSegment;
    const btScalar depthBehind = crossing ? behind : btScalar(0);
    local.distance = -depthBehind - reach;
    local.t = crossing ? (aIsFar ? btScalar(1) : btScalar(0)) : closest.s;
    const btVector3 onPlane = anchor + local.normal * depthBehind;
    local.pointOnBody = onPlane + local.normal * triangleMargin;
    local.pointOnCapsule = anchor - local.normal * capsule.radius;
  } else {
    // A degenerate (zero-area) triangle touched by the axis has no normal to push along.
    return false;
  }
  if (local.distance > margin) return false;
  contact = local;
  return true;
}

void triangleMeshContacts(const Capsule& capsule, const btConcaveShape& shape,
                          const btTransform& shapeToWorld, btScalar margin,
                          std::vector<Contact>& out) {
  const btTransform worldToShape = shapeToWorld.inverse();
  Capsule local = capsule;
  local.a = worldToShape * capsule.a;
  local.b = worldToShape * capsule.b;
  const btScalar triangleMargin = shape.getMargin();
  const btScalar grow = capsule.radius + margin + triangleMargin;
  btVector3 aabbMin = local.a;
  btVector3 aabbMax = local.a;
  aabbMin.setMin(local.b);
  aabbMax.setMax(local.b);
  aabbMin -= btVector3(grow, grow, grow);
  aabbMax += btVector3(grow, grow, grow);
  TriangleCollector collector(local, shapeToWorld, triangleMargin, margin, out);
  shape.processAllTriangles(&collector, aabbMin, aabbMax);
}

}  // namespace rope::bullet
