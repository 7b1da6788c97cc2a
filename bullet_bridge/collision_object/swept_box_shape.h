// SPDX-License-Identifier: MIT
#pragma once
// The collision shape of a rope capsule's broadphase object (capsule_proxies.h, kinematic_rope.h): an
// axis-aligned box of settable half extents around the object's origin, whose shape type stays
// EMPTY_SHAPE_PROXYTYPE, for which Bullet's collision configurations create no contact-generating
// algorithm (and whose processAllTriangles yields nothing, so Bullet's own ray and contact tests
// ignore it). The rope's own narrowphase handles every pair the box takes part in.
// Not API: installed only because capsule_proxies.h and kinematic_rope.h hold it; may change in any release.

#include <BulletCollision/CollisionShapes/btEmptyShape.h>

#include "bullet_bridge/bullet_precision.h"

namespace rope::bullet {

class SweptBoxShape : public btEmptyShape {
 public:
  void setHalfExtents(const btVector3& half) { half_ = half; }
  void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override {
    aabbMin = t.getOrigin() - half_;
    aabbMax = t.getOrigin() + half_;
  }

 private:
  btVector3 half_{0, 0, 0};
};

}  // namespace rope::bullet
