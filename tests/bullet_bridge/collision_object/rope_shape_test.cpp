// SPDX-License-Identifier: MIT
// A rope's capsule child (collision_object/rope_shape.h) answers Bullet's triangle callbacks: the exact
// ray entry and sphere cast, with the capsule's index, and otherwise a closed mesh on its surface.
#include "bullet_bridge/collision_object/rope_shape.h"

#include <gtest/gtest.h>

#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btRaycastCallback.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace rope::bullet {
namespace {

constexpr btScalar kRadius = btScalar(0.01), kHalfHeight = btScalar(0.02);

// Distance of a local point from the Y-axis capsule's surface.
double surfaceGap(const btVector3& p) {
  const btScalar y = std::clamp(p.y(), -kHalfHeight, kHalfHeight);
  return static_cast<double>((p - btVector3(0, y, 0)).length() - kRadius);
}

struct Triangles : btTriangleCallback {
  void processTriangle(btVector3* triangle, int, int) override {
    for (int i = 0; i < 3; ++i) vertices.push_back(triangle[i]);
  }
  std::vector<btVector3> vertices;
};

TEST(RopeCapsuleShape, GivesOtherCallbacksAClosedMeshOnItsSurface) {
  RopeCapsuleShape shape(kRadius, 4);
  shape.setHalfHeight(kHalfHeight);
  EXPECT_EQ(shape.getShapeType(), FAST_CONCAVE_MESH_PROXYTYPE);
  Triangles all;
  shape.processAllTriangles(&all, btVector3(-1, -1, -1), btVector3(1, 1, 1));
  ASSERT_EQ(all.vertices.size(), 3u * 256u);  // 16 sides, 9 bands, no degenerate triangle at the poles
  for (const btVector3& v : all.vertices) EXPECT_LT(std::abs(surfaceGap(v)), 1e-15);
  Triangles none;
  shape.processAllTriangles(&none, btVector3(1, 1, 1), btVector3(2, 2, 2));
  EXPECT_TRUE(none.vertices.empty());
}

TEST(RopeCapsuleShape, AabbIsTightForAnyOrientation) {
  RopeCapsuleShape shape(kRadius, 0);
  shape.setHalfHeight(kHalfHeight);
  const btTransform t(btQuaternion(btVector3(1, 2, 3).normalized(), btScalar(0.7)), btVector3(0.1, 0.2, 0.3));
  btVector3 lo, hi;
  shape.getAabb(t, lo, hi);
  // The extremes along each world axis: the end spheres' outermost points.
  const btVector3 axis = t.getBasis().getColumn(1);
  for (int k = 0; k < 3; ++k) {
    const double reach = std::abs(static_cast<double>(axis[k] * kHalfHeight)) + static_cast<double>(kRadius);
    EXPECT_NEAR(static_cast<double>(hi[k] - t.getOrigin()[k]), reach, 1e-15);
    EXPECT_NEAR(static_cast<double>(t.getOrigin()[k] - lo[k]), reach, 1e-15);
  }
}

struct Ray : btTriangleRaycastCallback {
  using btTriangleRaycastCallback::btTriangleRaycastCallback;
  btScalar reportHit(const btVector3& normal, btScalar fraction, int part, int index) override {
    ++hits;
    hitNormal = normal;
    partId = part;
    triangleIndex = index;
    return fraction;
  }
  int hits = 0, partId = 0, triangleIndex = 0;
  btVector3 hitNormal{0, 0, 0};
};

TEST(RopeCapsuleShape, AnswersARayExactlyWithItsIndex) {
  RopeCapsuleShape shape(kRadius, 7);
  shape.setHalfHeight(kHalfHeight);
  // Along -x at y = 0.005, z = 0.006: enters the cylinder at x = sqrt(r^2 - z^2) = 0.008.
  Ray ray(btVector3(1, 0.005, 0.006), btVector3(-1, 0.005, 0.006));
  shape.processAllTriangles(&ray, btVector3(-1, -1, -1), btVector3(1, 1, 1));
  ASSERT_EQ(ray.hits, 1);
  // To rounding: the quadratic's roots lose about 2e-15 of the 2 m ray (4e-15 m), the normal that
  // over the 1 cm radius.
  EXPECT_NEAR(static_cast<double>(ray.m_hitFraction), (1.0 - 0.008) / 2.0, 1e-14);
  EXPECT_NEAR(static_cast<double>(ray.hitNormal.x()), 0.8, 1e-12);
  EXPECT_NEAR(static_cast<double>(ray.hitNormal.z()), 0.6, 1e-12);
  EXPECT_EQ(ray.partId, -1);
  EXPECT_EQ(ray.triangleIndex, 7);
  // A closer hit found before: this capsule does not report a farther one.
  Ray behind(btVector3(1, 0.005, 0.006), btVector3(-1, 0.005, 0.006));
  behind.m_hitFraction = btScalar(0.4);
  shape.processAllTriangles(&behind, btVector3(-1, -1, -1), btVector3(1, 1, 1));
  EXPECT_EQ(behind.hits, 0);
}

struct SphereCast : btTriangleConvexcastCallback {
  using btTriangleConvexcastCallback::btTriangleConvexcastCallback;
  btScalar reportHit(const btVector3& normal, const btVector3& point, btScalar fraction, int, int index) override {
    ++hits;
    hitNormal = normal;
    hitPoint = point;
    triangleIndex = index;
    return fraction;
  }
  int hits = 0, triangleIndex = 0;
  btVector3 hitNormal{0, 0, 0}, hitPoint{0, 0, 0};
};

TEST(RopeCapsuleShape, AnswersASphereCastExactlyInTheWorldFrame) {
  RopeCapsuleShape shape(kRadius, 2);
  shape.setHalfHeight(kHalfHeight);
  // The capsule lies along world x (local y turned onto x), centred at (0, 1, 0); a 2 cm ball falls
  // from y = 2 onto its middle: contact when the centre is at 1 + r + 0.02.
  const btTransform capsuleToWorld(btQuaternion(btVector3(0, 0, 1), btScalar(-M_PI / 2)), btVector3(0, 1, 0));
  btSphereShape ball(btScalar(0.02));
  btTransform from = btTransform::getIdentity(), to = btTransform::getIdentity();
  from.setOrigin(btVector3(0.005, 2, 0));
  to.setOrigin(btVector3(0.005, 0, 0));
  SphereCast cast(&ball, from, to, capsuleToWorld, btScalar(0));
  shape.processAllTriangles(&cast, btVector3(-10, -10, -10), btVector3(10, 10, 10));
  ASSERT_EQ(cast.hits, 1);
  EXPECT_NEAR(static_cast<double>(cast.m_hitFraction), (2.0 - (1.0 + 0.01 + 0.02)) / 2.0, 1e-14);
  EXPECT_NEAR(static_cast<double>(cast.hitNormal.y()), 1.0, 1e-14);
  EXPECT_NEAR(static_cast<double>(cast.hitPoint.y()), 1.01, 1e-14);
  EXPECT_NEAR(static_cast<double>(cast.hitPoint.x()), 0.005, 1e-14);
  EXPECT_EQ(cast.triangleIndex, 2);
}

}  // namespace
}  // namespace rope::bullet
