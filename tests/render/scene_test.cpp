// SPDX-License-Identifier: MIT
#include "render/scene.h"

#include <gtest/gtest.h>

#include <cmath>

#include "render/primitive_mesh.h"
#include "rope/common/error.h"

namespace rope::render {
namespace {

TEST(Scene, BoundsCoverTransformedItemsButNotGround) {
  Scene scene;
  EXPECT_TRUE(scene.bounds().empty());
  auto box = std::make_shared<const Mesh>(makeBox(Vec3(1, 1, 1)));
  scene.add(box, Eigen::Isometry3d(Eigen::Translation3d(5, 0, 0)));
  auto ground = std::make_shared<const Mesh>(makeBox(Vec3(100, 0.1, 100)));
  scene.add(ground, Eigen::Isometry3d::Identity(), Rgb::Ones(), Material::Ground);
  EXPECT_TRUE(scene.hasGround());
  const BoundingBox bounds = scene.bounds();
  EXPECT_NEAR(bounds.min.x(), 4.0, 1e-6);
  EXPECT_NEAR(bounds.max.x(), 6.0, 1e-6);
  EXPECT_NEAR(bounds.max.z(), 1.0, 1e-6);
  scene.clear();
  EXPECT_TRUE(scene.items.empty());
}

TEST(Scene, AddValidatesMeshTransformAndColour) {
  Scene scene;
  auto mesh = std::make_shared<const Mesh>(makeBox(Vec3(1, 1, 1)));
  EXPECT_THROW(scene.add(nullptr), InvalidArgument);
  Eigen::Isometry3d broken = Eigen::Isometry3d::Identity();
  broken.translation().x() = std::nan("");
  try {
    scene.add(mesh, broken);
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.parameter(), "transform");
  }
  try {
    scene.add(mesh, Eigen::Isometry3d::Identity(), Rgb(0.5f, -0.1f, 0.5f));
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.parameter(), "colour[1]");
  }
  EXPECT_TRUE(scene.items.empty());
}

TEST(Mesh, AppendMovesPositionsAndRotatesNormals) {
  Mesh a = makeBox(Vec3(1, 1, 1));
  const Mesh b = makeBox(Vec3(1, 1, 1));
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.rotate(Eigen::AngleAxisd(0.5 * 3.14159265358979323846, Vec3::UnitZ()));
  t.pretranslate(Vec3(10, 0, 0));
  a.append(b, t);
  ASSERT_EQ(a.vertices.size(), 48u);
  ASSERT_EQ(a.indices.size(), 72u);
  EXPECT_EQ(a.indices[36], b.indices[0] + 24u);
  // Vertex 24 is b's vertex 0 moved: the +x face normal turned by 90 degrees about z points to +y.
  const Vertex& moved = a.vertices[24];
  const Vertex& original = b.vertices[0];
  const Vec3 expected = t * Vec3(original.position[0], original.position[1], original.position[2]);
  EXPECT_NEAR(moved.position[0], expected.x(), 1e-5);
  EXPECT_NEAR(moved.position[1], expected.y(), 1e-5);
  const Vec3 n = t.linear() * Vec3(original.normal[0], original.normal[1], original.normal[2]);
  EXPECT_NEAR(moved.normal[0], n.x(), 1e-6);
  EXPECT_NEAR(moved.normal[1], n.y(), 1e-6);
}

TEST(BoundingBox, EmptyUntilExtended) {
  BoundingBox box;
  EXPECT_TRUE(box.empty());
  box.extend(BoundingBox{});
  EXPECT_TRUE(box.empty());
  box.extend(Vec3(1, 2, 3));
  EXPECT_FALSE(box.empty());
  box.extend(Vec3(-1, 0, 3));
  EXPECT_TRUE(box.center().isApprox(Vec3(0, 1, 3)));
  EXPECT_NEAR(box.radius(), std::sqrt(2.0), 1e-12);
}

}  // namespace
}  // namespace rope::render
