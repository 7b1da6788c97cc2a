// SPDX-License-Identifier: MIT
#include "render/primitive_mesh.h"

#include <gtest/gtest.h>

#include <cmath>

#include "mesh_checks.h"
#include "rope/common/error.h"

namespace rope::render {
namespace {

using test::enclosedVolume;
using test::expectClosed;
using test::expectOutward;
using test::expectWellFormed;
constexpr double kPi = 3.14159265358979323846;

TEST(PrimitiveMesh, BoxHasFlatFacesAndExactVolume) {
  const Mesh box = makeBox(Vec3(0.5, 1.0, 1.5));
  EXPECT_EQ(box.vertices.size(), 24u);
  EXPECT_EQ(box.triangleCount(), 12u);
  expectWellFormed(box);
  expectClosed(box);
  expectOutward(box, Vec3::Zero());
  EXPECT_NEAR(enclosedVolume(box), 1.0 * 2.0 * 3.0, 1e-6);
  const BoundingBox bounds = meshBounds(box);
  EXPECT_NEAR(bounds.max.x(), 0.5, 1e-7);
  EXPECT_NEAR(bounds.min.z(), -1.5, 1e-7);
}

TEST(PrimitiveMesh, SphereVerticesLieOnTheSphereWithRadialNormals) {
  const Mesh sphere = makeSphere(0.7, 32);
  expectWellFormed(sphere);
  expectClosed(sphere);
  expectOutward(sphere, Vec3::Zero());
  for (const Vertex& v : sphere.vertices) {
    EXPECT_NEAR(test::position(v).norm(), 0.7, 1e-6);
    EXPECT_NEAR(test::normal(v).dot(test::position(v).normalized()), 1.0, 1e-6);
  }
  // An inscribed polyhedron: slightly less than the sphere's volume, converging with resolution.
  const double exact = 4.0 / 3.0 * kPi * std::pow(0.7, 3);
  EXPECT_LT(enclosedVolume(sphere), exact);
  EXPECT_GT(enclosedVolume(sphere), 0.95 * exact);
}

TEST(PrimitiveMesh, CapsuleSpansItsFullLength) {
  const Mesh capsule = makeCapsule(0.2, 0.5, 24);
  expectWellFormed(capsule);
  expectClosed(capsule);
  expectOutward(capsule, Vec3::Zero());
  const BoundingBox bounds = meshBounds(capsule);
  EXPECT_NEAR(bounds.max.y(), 0.7, 1e-6);
  EXPECT_NEAR(bounds.min.y(), -0.7, 1e-6);
  EXPECT_NEAR(bounds.max.x(), 0.2, 1e-6);
}

TEST(PrimitiveMesh, CylinderAndConeAreClosed) {
  const Mesh cylinder = makeCylinder(0.3, 0.4, 20);
  expectWellFormed(cylinder);
  expectClosed(cylinder);
  expectOutward(cylinder, Vec3::Zero());
  // Polygon area n/2 r^2 sin(2 pi/n) times the height.
  EXPECT_NEAR(enclosedVolume(cylinder), 10.0 * 0.09 * std::sin(2 * kPi / 20) * 0.8, 1e-6);
  const Mesh open = makeCylinder(0.3, 0.4, 20, false);
  EXPECT_EQ(open.triangleCount(), 40u);

  const Mesh cone = makeCone(0.3, 0.9, 24);
  expectWellFormed(cone);
  expectClosed(cone);
  expectOutward(cone, Vec3(0, -0.2, 0));
  const BoundingBox bounds = meshBounds(cone);
  EXPECT_NEAR(bounds.max.y(), 0.45, 1e-6);
  EXPECT_NEAR(bounds.min.y(), -0.45, 1e-6);
}

TEST(PrimitiveMesh, RejectsBadSizesAndResolutions) {
  EXPECT_THROW(makeBox(Vec3(1, 0, 1)), InvalidArgument);
  EXPECT_THROW(makeBox(Vec3(1, std::nan(""), 1)), InvalidArgument);
  EXPECT_THROW(makeSphere(-1.0, 16), InvalidArgument);
  EXPECT_THROW(makeSphere(1.0, 2), InvalidArgument);
  EXPECT_THROW(makeCapsule(0.1, -0.5, 16), InvalidArgument);
  EXPECT_THROW(makeCylinder(0.1, 0.5, 2000), InvalidArgument);
  EXPECT_THROW(makeCone(0.1, INFINITY, 16), InvalidArgument);
  try {
    makeSphere(0.0, 16);
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.parameter(), "radius");
  }
}

}  // namespace
}  // namespace rope::render
