// SPDX-License-Identifier: MIT
#include "render/shape_mesh_cache.h"

#include <btBulletCollisionCommon.h>
#include <gtest/gtest.h>

#include <memory>

#include "rope/common/error.h"

namespace rope::render {
namespace {

TEST(ShapeMeshCache, SameShapeSameMesh) {
  ShapeMeshCache cache;
  btBoxShape box(btVector3(1, 1, 1));
  const auto first = cache.get(box);
  const auto second = cache.get(box);
  EXPECT_EQ(first.get(), second.get());
  EXPECT_EQ(cache.buildCount(), 1u);
}

TEST(ShapeMeshCache, ResizedShapeIsRebuilt) {
  ShapeMeshCache cache;
  btSphereShape sphere(1.0);
  const auto before = cache.get(sphere);
  sphere.setUnscaledRadius(2.0);
  const auto after = cache.get(sphere);
  EXPECT_NE(before.get(), after.get());
  EXPECT_NEAR(meshBounds(*after).max.x(), 2.0, 1e-6);
  btBoxShape box(btVector3(1, 1, 1));
  cache.get(box);
  box.setLocalScaling(btVector3(1, 3, 1));
  EXPECT_NEAR(meshBounds(*cache.get(box)).max.y(), 3.0, 1e-5);
  EXPECT_EQ(cache.buildCount(), 4u);
  EXPECT_EQ(cache.size(), 2u);
}

TEST(ShapeMeshCache, AnotherShapeAtTheSameAddressIsNotConfused) {
  ShapeMeshCache cache;
  alignas(btSphereShape) alignas(btBoxShape) unsigned char storage[sizeof(btBoxShape) + sizeof(btSphereShape)];
  auto* sphere = new (storage) btSphereShape(1.0);
  const auto sphereMesh = cache.get(*sphere);
  sphere->~btSphereShape();
  auto* box = new (storage) btBoxShape(btVector3(1, 1, 1));
  const auto boxMesh = cache.get(*box);
  EXPECT_EQ(boxMesh->vertices.size(), 24u);
  box->~btBoxShape();
  EXPECT_NE(sphereMesh->vertices.size(), 24u);
  cache.clear();
  EXPECT_EQ(cache.size(), 0u);
}

TEST(ShapeMeshCache, RejectsBadOptionsAtConstruction) {
  ShapeMeshOptions options;
  options.curveSegments = 0;
  EXPECT_THROW(ShapeMeshCache{options}, InvalidArgument);
}

}  // namespace
}  // namespace rope::render
