// SPDX-License-Identifier: MIT
#include "render/shape_mesh.h"

#include <btBulletCollisionCommon.h>
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "mesh_checks.h"
#include "rope/common/error.h"

namespace rope::render {
namespace {

using test::enclosedVolume;
using test::expectClosed;
using test::expectOutward;
using test::expectWellFormed;
constexpr double kPi = 3.14159265358979323846;

// The mesh's bounds match Bullet's own AABB of the shape (within the collision margin, which
// Bullet adds to the AABB of most shapes but which is part of the visible surface only for some).
void expectBoundsLikeBullet(const btCollisionShape& shape, const Mesh& mesh, double tolerance) {
  btVector3 lo, hi;
  shape.getAabb(btTransform::getIdentity(), lo, hi);
  const BoundingBox bounds = meshBounds(mesh);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(bounds.min[i], lo[i], tolerance) << "axis " << i;
    EXPECT_NEAR(bounds.max[i], hi[i], tolerance) << "axis " << i;
  }
}

void expectClosedConvex(const Mesh& mesh) {
  ASSERT_FALSE(mesh.empty());
  expectWellFormed(mesh);
  expectClosed(mesh);
  expectOutward(mesh, meshBounds(mesh).center());
}

TEST(ShapeMesh, Box) {
  btBoxShape box(btVector3(0.2, 0.3, 0.4));
  const Mesh mesh = buildShapeMesh(box);
  expectClosedConvex(mesh);
  expectBoundsLikeBullet(box, mesh, 1e-6);
  EXPECT_NEAR(enclosedVolume(mesh), 0.4 * 0.6 * 0.8, 1e-6);
}

TEST(ShapeMesh, BoxWithLocalScaling) {
  btBoxShape box(btVector3(0.5, 0.5, 0.5));
  box.setLocalScaling(btVector3(2.0, 1.0, 0.5));
  const Mesh mesh = buildShapeMesh(box);
  EXPECT_NEAR(enclosedVolume(mesh), 2.0 * 1.0 * 0.5, 1e-5);
}

TEST(ShapeMesh, Sphere) {
  btSphereShape sphere(0.25);
  const Mesh mesh = buildShapeMesh(sphere);
  expectClosedConvex(mesh);
  expectBoundsLikeBullet(sphere, mesh, 1e-6);
  EXPECT_NEAR(enclosedVolume(mesh), 4.0 / 3.0 * kPi * std::pow(0.25, 3), 0.03 * std::pow(0.25, 3) * 4.2);
}

TEST(ShapeMesh, CapsuleOnEachAxis) {
  btCapsuleShapeX x(0.1, 0.6);
  btCapsuleShape y(0.1, 0.6);
  btCapsuleShapeZ z(0.1, 0.6);
  for (const btCapsuleShape* capsule : {static_cast<btCapsuleShape*>(&x), &y, static_cast<btCapsuleShape*>(&z)}) {
    const Mesh mesh = buildShapeMesh(*capsule);
    expectClosedConvex(mesh);
    expectBoundsLikeBullet(*capsule, mesh, 1e-6);
    const BoundingBox bounds = meshBounds(mesh);
    EXPECT_NEAR(bounds.max[capsule->getUpAxis()], 0.4, 1e-6);  // half height 0.3 + radius
  }
}

TEST(ShapeMesh, CylinderOnEachAxis) {
  btCylinderShapeX x(btVector3(0.5, 0.2, 0.2));
  btCylinderShape y(btVector3(0.2, 0.5, 0.2));
  btCylinderShapeZ z(btVector3(0.2, 0.2, 0.5));
  for (const btCylinderShape* cylinder : {static_cast<btCylinderShape*>(&x), &y, static_cast<btCylinderShape*>(&z)}) {
    const Mesh mesh = buildShapeMesh(*cylinder);
    expectClosedConvex(mesh);
    expectBoundsLikeBullet(*cylinder, mesh, 1e-6);
    EXPECT_NEAR(enclosedVolume(mesh), kPi * 0.04 * 1.0, 0.01);
  }
}

TEST(ShapeMesh, ConeOnEachAxis) {
  btConeShapeX x(0.3, 0.8);
  btConeShape y(0.3, 0.8);
  btConeShapeZ z(0.3, 0.8);
  for (const btConeShape* cone : {static_cast<btConeShape*>(&x), &y, static_cast<btConeShape*>(&z)}) {
    const Mesh mesh = buildShapeMesh(*cone);
    ASSERT_FALSE(mesh.empty());
    expectWellFormed(mesh);
    expectClosed(mesh);
    Vec3 centroid = Vec3::Zero();
    centroid[cone->getConeUpIndex()] = -0.2;  // inside, below the apex
    expectOutward(mesh, centroid);
    const BoundingBox bounds = meshBounds(mesh);
    EXPECT_NEAR(bounds.max[cone->getConeUpIndex()], 0.4, 1e-6);
    EXPECT_NEAR(enclosedVolume(mesh), kPi * 0.09 * 0.8 / 3.0, 0.003);
  }
}

TEST(ShapeMesh, ConvexHullOfACube) {
  btConvexHullShape hull;
  for (int i = 0; i < 8; ++i) hull.addPoint(btVector3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1), false);
  hull.addPoint(btVector3(0.1, 0.2, 0.3), false);  // interior point: ignored by the hull
  hull.recalcLocalAabb();
  const Mesh mesh = buildShapeMesh(hull);
  expectClosedConvex(mesh);
  EXPECT_EQ(mesh.triangleCount(), 12u);  // six quads, fanned
  EXPECT_NEAR(enclosedVolume(mesh), 8.0, 1e-5);
}

TEST(ShapeMesh, GenericConvexShapeThroughSupportMapping) {
  // A multi-sphere has no dedicated builder: it is meshed from its support mapping.
  const btVector3 centres[] = {btVector3(-0.5, 0, 0), btVector3(0.5, 0, 0)};
  const btScalar radii[] = {0.2, 0.3};
  btMultiSphereShape shape(centres, radii, 2);
  const Mesh mesh = buildShapeMesh(shape);
  expectClosedConvex(mesh);
  const BoundingBox bounds = meshBounds(mesh);
  EXPECT_NEAR(bounds.max.x(), 0.8, 0.02);
  EXPECT_NEAR(bounds.min.x(), -0.7, 0.02);
}

TEST(ShapeMesh, CompoundPlacesChildrenByTheirTransforms) {
  btCompoundShape compound;
  btBoxShape box(btVector3(0.1, 0.1, 0.1));
  btSphereShape sphere(0.2);
  compound.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(1, 0, 0)), &box);
  compound.addChildShape(btTransform(btQuaternion(btVector3(0, 1, 0), 0.5), btVector3(0, 2, 0)), &sphere);
  const Mesh mesh = buildShapeMesh(compound);
  const Mesh boxMesh = buildShapeMesh(box), sphereMesh = buildShapeMesh(sphere);
  EXPECT_EQ(mesh.vertices.size(), boxMesh.vertices.size() + sphereMesh.vertices.size());
  EXPECT_EQ(mesh.triangleCount(), boxMesh.triangleCount() + sphereMesh.triangleCount());
  expectWellFormed(mesh);
  expectClosed(mesh);
  const BoundingBox bounds = meshBounds(mesh);
  EXPECT_NEAR(bounds.max.x(), 1.1, 1e-6);
  EXPECT_NEAR(bounds.max.y(), 2.2, 1e-6);
  EXPECT_NEAR(enclosedVolume(mesh), enclosedVolume(boxMesh) + enclosedVolume(sphereMesh), 1e-6);
}

TEST(ShapeMesh, NestedCompound) {
  btSphereShape sphere(0.1);
  btCompoundShape inner;
  inner.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(0, 1, 0)), &sphere);
  btCompoundShape outer;
  outer.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(2, 0, 0)), &inner);
  const BoundingBox bounds = meshBounds(buildShapeMesh(outer));
  EXPECT_NEAR(bounds.center().x(), 2.0, 1e-6);
  EXPECT_NEAR(bounds.center().y(), 1.0, 1e-6);
}

TEST(ShapeMesh, PlaneIsALargeQuadFacingItsNormal) {
  btStaticPlaneShape plane(btVector3(0, 0, 2), 0.5);  // normalised by Bullet: z = 0.5
  EXPECT_TRUE(isPlaneShape(plane));
  ShapeMeshOptions options;
  options.planeHalfExtent = 10.0;
  const Mesh mesh = buildShapeMesh(plane, options);
  ASSERT_EQ(mesh.vertices.size(), 4u);
  ASSERT_EQ(mesh.triangleCount(), 2u);
  for (const Vertex& v : mesh.vertices) {
    EXPECT_NEAR(v.position[2], 0.5, 1e-6);
    EXPECT_NEAR(v.normal[2], 1.0, 1e-6);
  }
  const BoundingBox bounds = meshBounds(mesh);
  EXPECT_NEAR(bounds.max.x() - bounds.min.x(), 20.0, 1e-5);
  expectOutward(mesh, Vec3(0, 0, 0));
}

TEST(ShapeMesh, TriangleMeshThroughTheTriangleCallback) {
  btTriangleMesh triangles;
  triangles.addTriangle(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 0, -1));
  triangles.addTriangle(btVector3(1, 0, 0), btVector3(1, 0, -1), btVector3(0, 0, -1));
  triangles.addTriangle(btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(1, 0, 0));  // degenerate
  btBvhTriangleMeshShape shape(&triangles, true);
  const Mesh mesh = buildShapeMesh(shape);
  expectWellFormed(mesh);
  EXPECT_EQ(mesh.triangleCount(), 2u);  // the degenerate one is dropped
  for (const Vertex& v : mesh.vertices) EXPECT_NEAR(v.normal[1], 1.0, 1e-6);  // counter-clockwise from +y
  btScaledBvhTriangleMeshShape scaled(&shape, btVector3(2, 2, 2));
  const BoundingBox bounds = meshBounds(buildShapeMesh(scaled));
  EXPECT_NEAR(bounds.max.x(), 2.0, 1e-6);
}

TEST(ShapeMesh, HeightfieldIsConcaveAndMeshed) {
  std::vector<double> heights(5 * 5, 0.0);
  heights[12] = 1.0;  // a bump in the middle
  btHeightfieldTerrainShape terrain(5, 5, heights.data(), 0.0, 1.0, 1, false);
  const Mesh mesh = buildShapeMesh(terrain);
  expectWellFormed(mesh);
  EXPECT_EQ(mesh.triangleCount(), 4u * 4u * 2u);
}

TEST(ShapeMesh, EmptyShapeGivesAnEmptyMesh) {
  btEmptyShape empty;
  EXPECT_TRUE(buildShapeMesh(empty).empty());
}

TEST(ShapeMesh, RejectsBadOptions) {
  btSphereShape sphere(1.0);
  ShapeMeshOptions options;
  options.curveSegments = 2;
  EXPECT_THROW(buildShapeMesh(sphere, options), InvalidArgument);
  options = ShapeMeshOptions{};
  options.planeHalfExtent = -1.0;
  try {
    buildShapeMesh(sphere, options);
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.parameter(), "options.planeHalfExtent");
  }
}

}  // namespace
}  // namespace rope::render
