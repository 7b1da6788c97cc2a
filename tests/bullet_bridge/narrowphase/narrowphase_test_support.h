// SPDX-License-Identifier: MIT
#pragma once
// Shared helpers of the narrowphase tests: placed bodies, their contacts and vector comparisons.

#include <btBulletCollisionCommon.h>
#include <gtest/gtest.h>

#include <vector>

#include "bullet_bridge/capsule.h"
#include "bullet_bridge/contact.h"
#include "bullet_bridge/find_contacts.h"

namespace rope::bullet::test {

// A generic placement used by most tests, so that every analytic case is also checked rotated and
// translated: rotation of 0.7 rad about (1, 2, 3) and a translation of (0.3, -1.2, 2.5).
inline btTransform placement() {
  return btTransform(btQuaternion(btVector3(1, 2, 3).normalized(), btScalar(0.7)),
                     btVector3(btScalar(0.3), btScalar(-1.2), btScalar(2.5)));
}

// The capsule from a to b (given in the body's local frame) in the world frame.
inline Capsule worldCapsule(const btTransform& bodyToWorld, const btVector3& a, const btVector3& b,
                            btScalar radius) {
  Capsule capsule;
  capsule.a = bodyToWorld * a;
  capsule.b = bodyToWorld * b;
  capsule.radius = radius;
  return capsule;
}

// Contacts (findContacts) between a capsule given in the body's local frame and `shape` placed at
// placement().
inline std::vector<Contact> contactsWith(const btCollisionShape& shape, const btVector3& a,
                                         const btVector3& b, btScalar radius, double margin) {
  btCollisionObject object;
  object.setCollisionShape(const_cast<btCollisionShape*>(&shape));
  object.setWorldTransform(placement());
  std::vector<Contact> contacts;
  findContacts(worldCapsule(placement(), a, b, radius), object, margin, contacts);
  return contacts;
}

inline ::testing::AssertionResult vectorNear(const btVector3& actual, const btVector3& expected,
                                             double tolerance) {
  const double error = (actual - expected).length();
  if (error <= tolerance) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "(" << actual.x() << ", " << actual.y() << ", " << actual.z() << ") differs from ("
         << expected.x() << ", " << expected.y() << ", " << expected.z() << ") by " << error
         << " > " << tolerance;
}

}  // namespace rope::bullet::test
