// SPDX-License-Identifier: MIT
#include "bullet_bridge/narrowphase/concave_contact.h"

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <btBulletCollisionCommon.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "bullet_bridge/find_contacts.h"
#include "narrowphase_test_support.h"

namespace rope::bullet {
namespace {

using test::contactsWith;
using test::placement;
using test::vectorNear;

const Contact& deepest(const std::vector<Contact>& contacts) {
  return *std::min_element(contacts.begin(), contacts.end(),
                           [](const Contact& x, const Contact& y) { return x.distance < y.distance; });
}

void expectConsistent(const Contact& c) {
  EXPECT_NEAR(c.normal.length(), 1.0, 1e-12);
  EXPECT_TRUE(vectorNear(c.pointOnCapsule - c.pointOnBody, c.normal * c.distance, 1e-12));
  EXPECT_GE(c.t, 0.0);
  EXPECT_LE(c.t, 1.0);
}

TEST(PlaneContacts, TiltedCapsuleGivesOneContactPerEndWithinTheMargin) {
  btStaticPlaneShape plane(btVector3(0, 2, 0), 0.5);  // y = 0.5 after normalising the normal
  const btVector3 up = placement().getBasis() * btVector3(0, 1, 0);
  // End a 0.02 above the plane surface, end b penetrating 0.03; radius 0.1.
  auto contacts = contactsWith(plane, {0, 0.62, 0}, {1, 0.57, 0.3}, 0.1, 0.05);
  ASSERT_EQ(contacts.size(), 2u);
  EXPECT_EQ(contacts[0].t, 0.0);
  EXPECT_NEAR(contacts[0].distance, 0.02, 1e-12);
  EXPECT_EQ(contacts[1].t, 1.0);
  EXPECT_NEAR(contacts[1].distance, -0.03, 1e-12);
  for (const Contact& c : contacts) {
    expectConsistent(c);
    EXPECT_TRUE(vectorNear(c.normal, up, 1e-12));
    EXPECT_NEAR((placement().inverse() * c.pointOnBody).y(), 0.5, 1e-12);
  }
  // Raise end a beyond the margin: only end b remains.
  contacts = contactsWith(plane, {0, 0.66, 0}, {1, 0.57, 0.3}, 0.1, 0.05);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_EQ(contacts[0].t, 1.0);
  // A point-like axis gives one contact.
  EXPECT_EQ(contactsWith(plane, {0, 0.6, 0}, {0, 0.6, 0}, 0.1, 0.05).size(), 1u);
}

TEST(TriangleContact, SeparatedPenetratingAndCrossing) {
  const btVector3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  Capsule capsule;
  capsule.radius = 0.1;
  Contact contact;
  // Above the face with a triangle margin of 0.01: distance = 0.3 - 0.1 - 0.01.
  capsule.a = {0.5, 0.5, 0.3};
  capsule.b = {0.5, 0.5, 1.0};
  ASSERT_TRUE(triangleContact(capsule, a, b, c, 0.01, 0.5, contact));
  EXPECT_NEAR(contact.distance, 0.19, 1e-14);
  EXPECT_TRUE(vectorNear(contact.normal, {0, 0, 1}, 1e-14));
  EXPECT_TRUE(vectorNear(contact.pointOnBody, {0.5, 0.5, 0.01}, 1e-14));
  EXPECT_EQ(contact.t, 0.0);
  EXPECT_FALSE(triangleContact(capsule, a, b, c, 0.01, 0.18, contact));
  // Below the face (two-sided): normal -z.
  capsule.a = {0.5, 0.5, -0.15};
  capsule.b = {0.6, 0.5, -0.9};
  ASSERT_TRUE(triangleContact(capsule, a, b, c, 0, 0.1, contact));
  EXPECT_NEAR(contact.distance, 0.05, 1e-14);
  EXPECT_TRUE(vectorNear(contact.normal, {0, 0, -1}, 1e-14));
  // Crossing: 0.8 of the axis above, 0.2 below -> pushed up by 0.2 + r, at end b.
  capsule.a = {0.5, 0.5, 0.8};
  capsule.b = {0.5, 0.5, -0.2};
  ASSERT_TRUE(triangleContact(capsule, a, b, c, 0, 0, contact));
  EXPECT_NEAR(contact.distance, -0.3, 1e-14);
  EXPECT_TRUE(vectorNear(contact.normal, {0, 0, 1}, 1e-14));
  EXPECT_EQ(contact.t, 1.0);
  EXPECT_TRUE(vectorNear(contact.pointOnBody, {0.5, 0.5, 0}, 1e-14));
  EXPECT_TRUE(vectorNear(contact.pointOnCapsule, {0.5, 0.5, -0.3}, 1e-14));
  // Near an edge, outside the triangle: the normal points from the edge to the axis.
  capsule.a = {1, -0.3, -1};
  capsule.b = {1, -0.3, 1};
  ASSERT_TRUE(triangleContact(capsule, a, b, c, 0, 0.5, contact));
  EXPECT_NEAR(contact.distance, 0.2, 1e-14);
  EXPECT_TRUE(vectorNear(contact.normal, {0, -1, 0}, 1e-14));
  EXPECT_NEAR(contact.t, 0.5, 1e-14);
  // A zero-area triangle is never divided by.
  capsule.a = {0.5, 0.3, 0};
  capsule.b = {0.5, 0.3, 1};
  ASSERT_TRUE(triangleContact(capsule, a, b, {1, 0, 0}, 0, 0.5, contact));
  EXPECT_NEAR(contact.distance, 0.2, 1e-14);
}

// A flat 5 x 10 grid of unit quads in the x-z plane at y = 0 (100 triangles).
std::unique_ptr<btTriangleMesh> flatGrid() {
  auto mesh = std::make_unique<btTriangleMesh>();
  for (int i = 0; i < 10; ++i) {
    for (int k = 0; k < 5; ++k) {
      const btVector3 p00(i, 0, k), p10(i + 1, 0, k), p01(i, 0, k + 1), p11(i + 1, 0, k + 1);
      mesh->addTriangle(p00, p01, p10);
      mesh->addTriangle(p10, p01, p11);
    }
  }
  return mesh;
}

TEST(TriangleMeshContacts, CapsuleLyingOnAFlatMesh) {
  auto mesh = flatGrid();
  btBvhTriangleMeshShape shape(mesh.get(), true);
  ASSERT_EQ(mesh->getNumTriangles(), 100);
  shape.setMargin(0.02);  // Bullet inflates the triangles by the concave shape's margin
  const btVector3 up = placement().getBasis() * btVector3(0, 1, 0);
  const btScalar meshMargin = shape.getMargin();
  for (double gap : {0.03, -0.02}) {
    const btScalar y = 0.1 + meshMargin + gap;
    const auto contacts = contactsWith(shape, {2.3, y, 1.6}, {4.1, y, 2.2}, 0.1, 0.05);
    // The triangles under the axis are all at the gap; neighbours within the margin are farther.
    ASSERT_GT(contacts.size(), 4u);
    EXPECT_NEAR(deepest(contacts).distance, gap, 1e-12);
    EXPECT_TRUE(vectorNear(deepest(contacts).normal, up, 1e-12));
    int underTheAxis = 0;
    for (const Contact& c : contacts) {
      expectConsistent(c);
      EXPECT_GE(c.distance, gap - 1e-12);
      EXPECT_LE(c.distance, 0.05);
      if (std::fabs(c.distance - gap) < 1e-12) {
        ++underTheAxis;
        EXPECT_TRUE(vectorNear(c.normal, up, 1e-12));
      }
      EXPECT_GE(c.triangleIndex, 0);
      EXPECT_LT(c.triangleIndex, 100);
      EXPECT_EQ(c.partIndex, 0);
      EXPECT_EQ(c.childIndex, -1);
    }
    EXPECT_GE(underTheAxis, 4);
  }
  // Beyond the margin: nothing.
  const btScalar beyond = btScalar(0.151) + meshMargin;
  EXPECT_TRUE(contactsWith(shape, btVector3(2.3, beyond, 1.6), btVector3(4.1, beyond, 2.2), 0.1, 0.05)
                  .empty());
}

TEST(TriangleMeshContacts, EdgeOfTheMeshAndScaledMesh) {
  auto mesh = flatGrid();
  btBvhTriangleMeshShape shape(mesh.get(), true);
  // Beside the mesh edge x = 0, level with it: the contact normal is -x.
  const auto contacts = contactsWith(shape, {-0.25, 0, 1.2}, {-0.25, 0, 1.8}, 0.1, 0.2);
  ASSERT_FALSE(contacts.empty());
  const Contact& c = deepest(contacts);
  EXPECT_NEAR(c.distance, 0.15 - shape.getMargin(), 1e-12);
  EXPECT_TRUE(vectorNear(c.normal, placement().getBasis() * btVector3(-1, 0, 0), 1e-12));
  // Scaled by 2 in y: a mesh tilted by scaling would move; a flat one at y = 0 stays, but x
  // scaling by 2 moves the far edge from x = 10 to x = 20.
  btScaledBvhTriangleMeshShape scaled(&shape, btVector3(2, 1, 1));
  EXPECT_FALSE(contactsWith(scaled, {19.9, 0.15, 1}, {19.9, 0.15, 2}, 0.1, 0.1).empty());
  EXPECT_TRUE(contactsWith(shape, {19.9, 0.15, 1}, {19.9, 0.15, 2}, 0.1, 0.1).empty());
}

TEST(TriangleMeshContacts, HeightfieldSlope) {
  // Heights 0.5 * i on an 11 x 6 grid (unit spacing, y up): the local frame is centred on the
  // height range, so the surface is y = 0.5 x in the shape's frame (x from -5 to 5).
  const int width = 11, length = 6;
  std::vector<double> heights(width * length);
  for (int j = 0; j < length; ++j) {
    for (int i = 0; i < width; ++i) heights[j * width + i] = 0.5 * i;
  }
  btHeightfieldTerrainShape terrain(width, length, heights.data(), 0.0, 5.0, 1, false);
  terrain.setMargin(0.01);
  const btVector3 n = btVector3(-0.5, 1, 0).normalized();
  const btVector3 onSurface(1.0, 0.5, 0.3);
  const btScalar m = terrain.getMargin();
  for (double gap : {0.04, -0.03}) {
    const btVector3 a = onSurface + n * (0.1 + m + gap);
    const auto contacts = contactsWith(terrain, a, a + n * 0.5 + btVector3(0, 0, 0.2), 0.1, 0.05);
    ASSERT_FALSE(contacts.empty()) << gap;
    const Contact& c = deepest(contacts);
    expectConsistent(c);
    EXPECT_NEAR(c.distance, gap, 1e-12);
    EXPECT_TRUE(vectorNear(c.normal, placement().getBasis() * n, 1e-12));
    EXPECT_TRUE(vectorNear(c.pointOnBody, placement() * (onSurface + n * m), 1e-12));
    EXPECT_EQ(c.t, 0.0);
  }
}

}  // namespace
}  // namespace rope::bullet
