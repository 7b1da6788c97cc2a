// SPDX-License-Identifier: MIT
#include "bullet_bridge/narrowphase/convex_contact.h"

#include <btBulletCollisionCommon.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "bullet_bridge/find_contacts.h"
#include "narrowphase_test_support.h"

namespace rope::bullet {
namespace {

using test::contactsWith;
using test::placement;
using test::vectorNear;

constexpr double kExact = 1e-9;

// Checks one contact against an analytic distance and local-frame normal / body point, plus the
// convention pointOnCapsule - pointOnBody = distance * normal.
void expectContact(const std::vector<Contact>& contacts, double distance,
                   const btVector3& localNormal, const btVector3& localPointOnBody,
                   double tolerance = kExact) {
  ASSERT_EQ(contacts.size(), 1u);
  const Contact& c = contacts[0];
  EXPECT_NEAR(c.distance, distance, tolerance);
  EXPECT_TRUE(vectorNear(c.normal, placement().getBasis() * localNormal.normalized(), tolerance));
  EXPECT_TRUE(vectorNear(c.pointOnBody, placement() * localPointOnBody, tolerance));
  EXPECT_TRUE(vectorNear(c.pointOnCapsule - c.pointOnBody, c.normal * c.distance, 1e-12));
  EXPECT_NEAR(c.normal.length(), 1.0, 1e-12);
  EXPECT_GE(c.t, 0.0);
  EXPECT_LE(c.t, 1.0);
  EXPECT_EQ(c.childIndex, -1);
  EXPECT_EQ(c.triangleIndex, -1);
}

TEST(ConvexContact, BoxFaceUsesTheFullExtentsIncludingBulletsMargin) {
  btBoxShape box(btVector3(1, 0.5, 0.25));
  // Bullet stores the extents minus the margin; the true box is without-margin + margin.
  ASSERT_NEAR(box.getHalfExtentsWithoutMargin().y() + box.getMargin(), 0.5, 1e-15);
  const btScalar r = 0.1;
  // Speculative: axis at 0.5 + r + 0.03 above the +y face, margin 0.05 -> distance 0.03.
  // The axis is parallel to the face, so any closest point along it is correct: check its height.
  auto contacts = contactsWith(box, {-0.5, 0.63, -0.1}, {0.5, 0.63, 0.1}, r, 0.05);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_NEAR(contacts[0].distance, 0.03, kExact);
  EXPECT_TRUE(vectorNear(contacts[0].normal, placement().getBasis() * btVector3(0, 1, 0), kExact));
  EXPECT_NEAR((placement().inverse() * contacts[0].pointOnBody).y(), 0.5, kExact);
  EXPECT_NEAR((placement().inverse() * contacts[0].pointOnCapsule).y(), 0.53, kExact);
  // Penetrating by 0.04 (axis still outside the box).
  expectContact(contactsWith(box, {0, 0.56, 0}, {0, 0.56, 0}, r, 0.0), -0.04, {0, 1, 0},
                {0, 0.5, 0});
  // Beyond the margin: no contact.
  EXPECT_TRUE(contactsWith(box, {-0.5, 0.6500001, 0}, {0.5, 0.6500001, 0}, r, 0.05).empty());
}

TEST(ConvexContact, BoxMarginSettingKeepsTheTrueExtents) {
  btBoxShape box(btVector3(1, 1, 1));
  box.setMargin(0.2);
  expectContact(contactsWith(box, {1.35, 0, 0}, {1.6, 0.2, 0}, 0.25, 0.5), 0.1, {1, 0, 0},
                {1, 0, 0});
}

TEST(ConvexContact, BoxEdgeAndCorner) {
  btBoxShape box(btVector3(1, 0.5, 0.25));
  const btScalar r = 0.05;
  // Edge (x = 1, y = 0.5) and a z-direction capsule 0.2 away diagonally.
  const btVector3 diagonal = btVector3(1, 1, 0).normalized();
  const btVector3 edgePoint(1, 0.5, 0.1);
  expectContact(contactsWith(box, edgePoint + diagonal * 0.2,
                             edgePoint + diagonal * 0.7 + btVector3(0, 0, 0.1), r, 0.2),
                0.15, diagonal, edgePoint);
  // Corner and a capsule pointing away from it.
  const btVector3 corner(1, 0.5, 0.25), out = btVector3(1, 2, 3).normalized();
  const auto contacts = contactsWith(box, corner + out * 0.08, corner + out * 1.0, r, 0.1);
  expectContact(contacts, 0.03, out, corner);
  EXPECT_EQ(contacts[0].t, 0.0);
}

TEST(ConvexContact, DeepPenetrationUsesMprOnTheInflatedCapsule) {
  btBoxShape box(btVector3(1, 0.5, 0.25));
  // Axis inside the box, 0.1 below the top face: the minimum translation is 0.1 + r up, and the
  // ray between the centres runs along it, so MPR is exact here.
  const auto contacts = contactsWith(box, {-0.5, 0.4, 0}, {0.5, 0.4, 0}, 0.1, 0.05);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_NEAR(contacts[0].distance, -0.2, 1e-9);
  EXPECT_TRUE(vectorNear(contacts[0].normal, placement().getBasis() * btVector3(0, 1, 0), 1e-9));
  EXPECT_NEAR((placement().inverse() * contacts[0].pointOnBody).y(), 0.5, 1e-9);
  EXPECT_TRUE(vectorNear(contacts[0].pointOnCapsule - contacts[0].pointOnBody,
                         contacts[0].normal * contacts[0].distance, 1e-12));
}

TEST(ConvexContact, DeepDegenerateConfigurationsStayFinite) {
  // Coincident centres (libccd's first portal direction is then zero), an axis through the body
  // centre, a point-like axis at the centre: finite contacts with a unit normal, no FP trap.
  btBoxShape box(btVector3(1, 0.5, 0.25));
  btSphereShape sphere(0.5);
  btCylinderShape cylinder(btVector3(0.5, 1, 0.5));
  const btCollisionShape* shapes[3] = {&box, &sphere, &cylinder};
  for (const btCollisionShape* shape : shapes) {
    for (const auto& ends : {std::pair<btVector3, btVector3>({-0.3, 0, 0}, {0.3, 0, 0}),
                             std::pair<btVector3, btVector3>({0, 0, 0}, {0, 0, 0}),
                             std::pair<btVector3, btVector3>({0, -0.2, 0}, {0, 0.2, 0}),
                             std::pair<btVector3, btVector3>({0.1, -2, 0.05}, {-0.1, 2, 0.0})}) {
      const auto contacts = contactsWith(*shape, ends.first, ends.second, 0.05, 0.01);
      ASSERT_EQ(contacts.size(), 1u) << shape->getName();
      const Contact& c = contacts[0];
      EXPECT_TRUE(std::isfinite(c.distance));
      EXPECT_LT(c.distance, -0.05) << shape->getName();
      EXPECT_NEAR(c.normal.length(), 1.0, 1e-9) << shape->getName();
      EXPECT_TRUE(vectorNear(c.pointOnCapsule - c.pointOnBody, c.normal * c.distance, 1e-12));
    }
  }
  // The sphere with the axis through its centre: the minimum translation is sideways, by
  // radius + r (along the axis it would be 0.85).
  const auto contacts = contactsWith(sphere, {-0.3, 0, 0}, {0.3, 0, 0}, 0.05, 0.01);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_NEAR(contacts[0].distance, -0.55, 1e-9);
  EXPECT_NEAR(contacts[0].normal.dot(placement().getBasis() * btVector3(1, 0, 0)), 0.0, 1e-9);
}

TEST(ConvexContact, DeepContactPushesTheRopeSideways) {
  // A long capsule whose axis runs through a small box off its centre line: the ray from the box
  // centre to the nearest axis point is the minimum translation (0.3 - 0.1 + r along y; along z
  // it would be 0.4 + r, along the rope 1 + 0.5 + r).
  btBoxShape box(btVector3(0.5, 0.3, 0.4));
  const auto contacts = contactsWith(box, {-3, 0.1, 0}, {1, 0.1, 0}, 0.05, 0.02);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_NEAR(contacts[0].distance, -0.25, 1e-9);
  EXPECT_TRUE(vectorNear(contacts[0].normal, placement().getBasis() * btVector3(0, 1, 0), 1e-9));
  EXPECT_NEAR(contacts[0].t, 0.75, 1e-9);
  EXPECT_NEAR((placement().inverse() * contacts[0].pointOnBody).y(), 0.3, 1e-9);
}

TEST(ConvexContact, SphereNearTheCapsuleEndIsExact) {
  // The sphere sits near one end of a long capsule, where the ray between the centres is far from
  // the contact normal: a pure MPR depth would be wrong here, the GJK distance is exact.
  btSphereShape sphere(0.1);
  const btVector3 centre(0, 0, 0);
  const btVector3 a(-1.9, 0.25, 0), b(0.1, 0.25, 0);  // axis 0.25 above the sphere centre
  expectContact(contactsWith(sphere, a, b, 0.1, 0.1), 0.05, {0, 1, 0}, {0, 0.1, 0});
  expectContact(contactsWith(sphere, a - btVector3(0, 0.1, 0), b - btVector3(0, 0.1, 0), 0.1, 0.0),
                -0.05, {0, 1, 0}, {0, 0.1, 0});
  EXPECT_TRUE(contactsWith(sphere, a, b, 0.1, 0.0499).empty());
}

TEST(ConvexContact, CapsuleVsCapsuleAllUpAxes) {
  btCapsuleShapeX capsuleX(0.2, 1.0);  // radius 0.2, axis from x = -0.5 to 0.5
  btCapsuleShape capsuleY(0.2, 1.0);
  btCapsuleShapeZ capsuleZ(0.2, 1.0);
  const btCapsuleShape* shapes[3] = {&capsuleX, &capsuleY, &capsuleZ};
  for (int axis = 0; axis < 3; ++axis) {
    const btVector3 up(axis == 0, axis == 1, axis == 2);
    const btVector3 side(axis == 1, axis == 2, axis == 0);
    const btVector3 across = up.cross(side);
    // Skew: a capsule along `across`, 0.45 from the body's axis at height 0.3 along it.
    const btVector3 centre = up * 0.3 + side * 0.45;
    expectContact(contactsWith(*shapes[axis], centre - across, centre + across, 0.05, 0.5), 0.2,
                  side, up * 0.3 + side * 0.2);
    // Beyond the body's axis end: end-cap sphere contact.
    const btVector3 beyond = up * 0.9;
    expectContact(contactsWith(*shapes[axis], beyond - across, beyond + across, 0.05, 0.5), 0.15,
                  up, up * 0.7);
  }
}

TEST(ConvexContact, CylinderSideAndCapAllUpAxes) {
  btCylinderShapeX cylinderX(btVector3(0.8, 0.5, 0.5));
  btCylinderShape cylinderY(btVector3(0.5, 0.8, 0.5));
  btCylinderShapeZ cylinderZ(btVector3(0.5, 0.5, 0.8));
  const btCylinderShape* shapes[3] = {&cylinderX, &cylinderY, &cylinderZ};
  for (int axis = 0; axis < 3; ++axis) {
    const btVector3 up(axis == 0, axis == 1, axis == 2);
    const btVector3 side(axis == 1, axis == 2, axis == 0);
    const btVector3 across = up.cross(side);
    // Side: parallel to the axis, capsule surface 0.02 from the mantle (radius 0.5).
    expectContact(contactsWith(*shapes[axis], side * 0.62, side * 0.92 + up * 0.2, 0.1, 0.05),
                  0.02, side, side * 0.5, 1e-8);
    // Cap: across the cap, penetrating 0.01.
    expectContact(contactsWith(*shapes[axis], up * 0.89, up * 1.19 + across * 0.2, 0.1, 0.05),
                  -0.01, up, up * 0.8, 1e-8);
  }
}

TEST(ConvexContact, ConeSlantIncludesBulletsMargin) {
  btConeShape cone(0.6, 0.8);  // base radius 0.6 at y = -0.4, apex at y = 0.4
  const btScalar coneMargin = cone.getMargin();
  ASSERT_GT(coneMargin, 0.0);
  const btVector3 apex(0, 0.4, 0), rim(0.6, -0.4, 0);
  const btVector3 normal = btVector3(0.8, 0.6, 0).normalized();
  const btVector3 mid = (apex + rim) / 2;
  const btVector3 along = (apex - rim).normalized();
  // Capsule parallel to the generator, its axis 0.2 from the sharp cone.
  const btScalar r = 0.05;
  expectContact(contactsWith(cone, mid + normal * 0.2, mid + normal * 0.5 + along * 0.1, r, 0.2),
                0.2 - r - coneMargin, normal, mid + normal * coneMargin, 1e-8);
}

TEST(ConvexContact, ConeUpAxisVariants) {
  btConeShapeX coneX(0.5, 1.0);
  btConeShapeZ coneZ(0.5, 1.0);
  const btScalar m = coneX.getMargin();
  // A point-like capsule straight beyond the apex: distance = gap - r - margin.
  expectContact(contactsWith(coneX, {0.8, 0, 0}, {1.5, 0, 0}, 0.1, 0.5), 0.2 - m, {1, 0, 0},
                btVector3(btScalar(0.5) + m, 0, 0));
  expectContact(contactsWith(coneZ, {0, 0, -0.8}, {0, 0, -1.5}, 0.1, 0.5), 0.2 - m, {0, 0, -1},
                btVector3(0, 0, btScalar(-0.5) - m));
}

TEST(ConvexContact, ConvexHullTetrahedronWithMargin) {
  btConvexHullShape hull;
  hull.addPoint(btVector3(0, 0, 0), false);
  hull.addPoint(btVector3(1, 0, 0), false);
  hull.addPoint(btVector3(0, 1, 0), false);
  hull.addPoint(btVector3(0, 0, 1), true);
  hull.setMargin(0.03);
  const btVector3 n = btVector3(1, 1, 1).normalized();
  const btVector3 faceCentre(1.0 / 3, 1.0 / 3, 1.0 / 3);
  const btVector3 tangent = btVector3(1, -1, 0).normalized();
  // Parallel to the slanted face, axis 0.25 from it: distance = 0.25 - r - hull margin.
  expectContact(contactsWith(hull, faceCentre + n * 0.25, faceCentre + n * 0.5 + tangent * 0.1,
                             0.1, 0.2),
                0.12, n, faceCentre + n * 0.03);
  // Vertex region of the origin vertex.
  const btVector3 out = btVector3(-1, -2, -2).normalized();
  expectContact(contactsWith(hull, out * 0.5, out * 0.9, 0.1, 0.5), 0.37, out, out * 0.03);
  // Scaled hull: the scaled points are used.
  hull.setLocalScaling(btVector3(2, 2, 2));
  expectContact(contactsWith(hull, {0.5, 0.5, -0.3}, {0.6, 0.4, -0.8}, 0.1, 0.5), 0.17, {0, 0, -1},
                {0.5, 0.5, -0.03}, 1e-8);
}

TEST(ConvexContact, SpeculativeContactsReportTheExactGapUpToTheMargin) {
  btSphereShape sphere(0.5);
  const double margin = 0.1;
  for (double gap : {1e-6, 0.01, 0.05, 0.0999999}) {
    const auto contacts =
        contactsWith(sphere, btVector3(-0.3, btScalar(0.6 + gap), 0),
                     btVector3(0.3, btScalar(0.6 + gap), 0), 0.1, margin);
    ASSERT_EQ(contacts.size(), 1u) << gap;
    EXPECT_GT(contacts[0].distance, 0.0);
    EXPECT_LE(contacts[0].distance, margin);
    EXPECT_NEAR(contacts[0].distance, gap, 1e-12);
  }
  EXPECT_TRUE(contactsWith(sphere, {-0.3, 0.7000001, 0}, {0.3, 0.7000001, 0}, 0.1, margin).empty());
}

TEST(ConvexContact, BoxAndTheHullOfItsCornersAgreeOnRandomCapsules) {
  // Two descriptions of one solid: a btBoxShape (sharp, true extents) and the hull of its corners
  // with zero margin, under the same rotated placement.
  const btVector3 half(0.6, 0.25, 0.4);
  btBoxShape box(half);
  btConvexHullShape hull;
  for (int corner = 0; corner < 8; ++corner) {
    hull.addPoint(btVector3(corner & 1 ? half.x() : -half.x(), corner & 2 ? half.y() : -half.y(),
                            corner & 4 ? half.z() : -half.z()),
                  false);
  }
  hull.recalcLocalAabb();
  hull.setMargin(0);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  int compared = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const btVector3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
    const auto fromBox = contactsWith(box, a, b, 0.05, 0.3);
    const auto fromHull = contactsWith(hull, a, b, 0.05, 0.3);
    ASSERT_EQ(fromBox.size(), fromHull.size()) << "trial " << trial;
    if (fromBox.empty() || fromBox[0].distance < -0.05) continue;  // deep: MPR estimates
    EXPECT_NEAR(fromBox[0].distance, fromHull[0].distance, 1e-12) << "trial " << trial;
    ++compared;
  }
  EXPECT_GT(compared, 50);
}

TEST(ConvexContact, CoreDescriptionsFollowBulletConventions) {
  ConvexCore core;
  btSphereShape sphere(0.7);
  ASSERT_TRUE(makeConvexCore(sphere, core));
  EXPECT_EQ(core.rounding, btScalar(0.7));
  btCapsuleShapeZ capsule(0.2, 1.0);
  ASSERT_TRUE(makeConvexCore(capsule, core));
  EXPECT_EQ(core.upAxis, 2);
  EXPECT_NEAR(core.halfHeight, 0.5, 1e-15);
  EXPECT_NEAR(core.rounding, 0.2, 1e-15);
  btBoxShape box(btVector3(1, 2, 3));
  box.setLocalScaling(btVector3(2, 1, 1));
  ASSERT_TRUE(makeConvexCore(box, core));
  EXPECT_TRUE(vectorNear(core.halfExtents, {2, 2, 3}, 1e-12));
  EXPECT_EQ(core.rounding, 0.0);
  btCylinderShapeZ cylinder(btVector3(0.3, 0.3, 2));
  ASSERT_TRUE(makeConvexCore(cylinder, core));
  EXPECT_NEAR(core.radius, 0.3, 1e-15);
  EXPECT_NEAR(core.halfHeight, 2, 1e-15);
  const btVector3 position(0, 0, 0);
  const btScalar radius = 0.5;
  btMultiSphereShape multiSphere(&position, &radius, 1);
  EXPECT_FALSE(makeConvexCore(multiSphere, core));
}

}  // namespace
}  // namespace rope::bullet
