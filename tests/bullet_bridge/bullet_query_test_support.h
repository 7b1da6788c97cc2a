// SPDX-License-Identifier: MIT
#pragma once
// Helpers for the tests that call Bullet's own queries on ropes.

#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>

#include <algorithm>
#include <limits>

namespace rope::bullet::test {

// A free collision object (no body) of `shape` at `at`, unrotated: a probe for contactTest.
inline void placeProbe(btCollisionObject& probe, btCollisionShape& shape, const btVector3& at) {
  probe.setCollisionShape(&shape);
  probe.getWorldTransform().setIdentity();
  probe.getWorldTransform().setOrigin(at);
}

// Counts the contact points a query reports and keeps the deepest (the least distance, m).
struct DeepestContact : btCollisionWorld::ContactResultCallback {
  btScalar addSingleResult(btManifoldPoint& point, const btCollisionObjectWrapper*, int, int,
                           const btCollisionObjectWrapper*, int, int) override {
    ++count;
    distance = std::min(distance, static_cast<double>(point.getDistance()));
    return 0;
  }
  int count = 0;
  double distance = std::numeric_limits<double>::infinity();
};

}  // namespace rope::bullet::test
