// SPDX-License-Identifier: MIT
#include "bullet_bridge/find_contacts.h"

#include <btBulletCollisionCommon.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "narrowphase/narrowphase_test_support.h"
#include "rope/common/error.h"

namespace rope::bullet {
namespace {

using test::placement;
using test::vectorNear;
using test::worldCapsule;

// Runs findContacts expecting InvalidArgument for `parameter`, with `text` in the message, and
// `out` untouched.
void expectInvalid(const Capsule& capsule, const btCollisionObject& object, double margin,
                   const std::string& parameter, const std::string& text) {
  std::vector<Contact> out(1);
  try {
    findContacts(capsule, object, margin, out);
    ADD_FAILURE() << "no exception for " << parameter;
  } catch (const InvalidArgument& error) {
    EXPECT_EQ(error.parameter(), parameter);
    EXPECT_NE(std::string(error.what()).find(text), std::string::npos) << error.what();
  }
  EXPECT_EQ(out.size(), 1u);
}

TEST(FindContacts, CompoundChildrenWithOffsetAndRotatedTransforms) {
  btBoxShape box(btVector3(0.5, 0.2, 0.3));
  btSphereShape sphere(0.25);
  btCompoundShape compound;
  const btTransform boxPlace(btQuaternion(btVector3(0, 0, 1), SIMD_HALF_PI), btVector3(2, 0, 0));
  compound.addChildShape(boxPlace, &box);
  compound.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(-2, 0, 0)), &sphere);
  btCollisionObject object;
  object.setCollisionShape(&compound);
  object.setWorldTransform(placement());

  // The box child is turned by 90 degrees about z: its 0.5 half extent now lies along y, so its
  // top face is at y = 0.5 in the compound frame.
  std::vector<Contact> contacts;
  findContacts(worldCapsule(placement(), {1.9, 0.62, 0}, {2.1, 0.9, 0.1}, 0.1), object, 0.05,
               contacts);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_EQ(contacts[0].childIndex, 0);
  EXPECT_NEAR(contacts[0].distance, 0.02, 1e-9);
  EXPECT_TRUE(vectorNear(contacts[0].normal, placement().getBasis() * btVector3(0, 1, 0), 1e-9));
  EXPECT_TRUE(vectorNear(contacts[0].pointOnBody, placement() * btVector3(1.9, 0.5, 0), 1e-9));

  // The sphere child, appended after the existing contact.
  findContacts(worldCapsule(placement(), {-2, 0, 0.4}, {-2, 0, 0.9}, 0.1), object, 0.1,
               contacts);
  ASSERT_EQ(contacts.size(), 2u);
  EXPECT_EQ(contacts[1].childIndex, 1);
  EXPECT_NEAR(contacts[1].distance, 0.05, 1e-12);
  EXPECT_TRUE(vectorNear(contacts[1].normal, placement().getBasis() * btVector3(0, 0, 1), 1e-12));
}

TEST(FindContacts, NestedCompoundReportsTheTopLevelChild) {
  btSphereShape sphere(0.25);
  btCompoundShape inner;
  inner.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(0, 1, 0)), &sphere);
  btCompoundShape outer;
  btSphereShape spare(0.1);
  outer.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(5, 0, 0)), &spare);
  outer.addChildShape(btTransform(btQuaternion(btVector3(1, 0, 0), SIMD_HALF_PI), btVector3(0, 0, 1)),
                      &inner);
  btCollisionObject object;
  object.setCollisionShape(&outer);
  object.setWorldTransform(placement());
  // The inner child's sphere centre: rotate (0, 1, 0) by 90 degrees about x -> (0, 0, 1), plus
  // (0, 0, 1) -> (0, 0, 2).
  std::vector<Contact> contacts;
  findContacts(worldCapsule(placement(), {0, 0, 2.4}, {0, 0, 3}, 0.1), object, 0.1, contacts);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_EQ(contacts[0].childIndex, 1);
  EXPECT_NEAR(contacts[0].distance, 0.05, 1e-12);
  EXPECT_TRUE(vectorNear(contacts[0].pointOnBody, placement() * btVector3(0, 0, 2.25), 1e-12));
}

TEST(FindContacts, BadInputNamesTheParameter) {
  btSphereShape sphere(0.5);
  btCollisionObject object;
  object.setCollisionShape(&sphere);
  Capsule capsule;
  capsule.a = {0, 1, 0};
  capsule.b = {1, 1, 0};
  capsule.radius = 0.1;
  const double nan = std::numeric_limits<double>::quiet_NaN();

  Capsule bad = capsule;
  bad.a.setY(nan);
  expectInvalid(bad, object, 0.1, "capsule.a.y", "nan");
  bad = capsule;
  bad.b.setZ(std::numeric_limits<double>::infinity());
  expectInvalid(bad, object, 0.1, "capsule.b.z", "inf");
  bad = capsule;
  bad.radius = -0.1;
  expectInvalid(bad, object, 0.1, "capsule.radius", "-0.1");
  bad.radius = 0;
  expectInvalid(bad, object, 0.1, "capsule.radius", "must be > 0");
  expectInvalid(capsule, object, -0.01, "margin", "-0.01");
  expectInvalid(capsule, object, nan, "margin", "nan");
}

TEST(FindContacts, UnsupportedShapesNameTheShapeType) {
  Capsule capsule;
  capsule.a = {0, 1, 0};
  capsule.b = {1, 1, 0};
  capsule.radius = 0.1;
  const btVector3 position(0, 0, 0);
  const btScalar radius = 0.5;
  btMultiSphereShape multiSphere(&position, &radius, 1);
  btCollisionObject object;
  object.setCollisionShape(&multiSphere);
  expectInvalid(capsule, object, 0.1, "object.shape", "MultiSphere");

  // Also inside a compound, even after a supported child: nothing is appended.
  btSphereShape sphere(1.0);
  btCompoundShape compound;
  compound.addChildShape(btTransform::getIdentity(), &sphere);
  compound.addChildShape(btTransform::getIdentity(), &multiSphere);
  object.setCollisionShape(&compound);
  expectInvalid(capsule, object, 0.1, "object.shape", "MultiSphere");

  btCollisionObject empty;
  expectInvalid(capsule, empty, 0.1, "object.shape", "no shape");
}

}  // namespace
}  // namespace rope::bullet
