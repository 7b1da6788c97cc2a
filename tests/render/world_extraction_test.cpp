// SPDX-License-Identifier: MIT
#include "render/world_extraction.h"

#include <btBulletCollisionCommon.h>
#include <gtest/gtest.h>

#include "rope/common/error.h"
#include "test_scene.h"

namespace rope::render {
namespace {

TEST(WorldExtraction, OneItemPerObjectPlacedByItsWorldTransform) {
  test::TestWorld world;
  ShapeMeshCache cache;
  Scene scene;
  extractWorld(world.world, cache, scene);
  ASSERT_EQ(scene.items.size(), world.objects.size());
  for (std::size_t i = 0; i < scene.items.size(); ++i) {
    const btTransform& t = world.objects[i]->getWorldTransform();
    const Vec3 origin(t.getOrigin().x(), t.getOrigin().y(), t.getOrigin().z());
    EXPECT_LT((scene.items[i].transform.translation() - origin).norm(), 1e-12);
  }
  // The plane becomes ground, everything else a surface; the ground is not part of the bounds.
  EXPECT_EQ(scene.items[0].material, Material::Ground);
  EXPECT_TRUE(scene.hasGround());
  for (std::size_t i = 1; i < scene.items.size(); ++i) EXPECT_EQ(scene.items[i].material, Material::Surface);
  const BoundingBox bounds = scene.bounds();
  EXPECT_NEAR(bounds.min.y(), 0.0, 0.01);
  EXPECT_LT(bounds.max.x() - bounds.min.x(), 5.0);
}

TEST(WorldExtraction, WorldTransformRotatesTheMesh) {
  test::TestWorld world;
  ShapeMeshCache cache;
  Scene scene;
  world.box->getWorldTransform().setRotation(btQuaternion(btVector3(0, 1, 0), 0.25 * 3.14159265358979323846));
  extractWorld(world.world, cache, scene);
  const DrawItem& box = scene.items[1];
  const BoundingBox bounds = meshBounds(*box.mesh, box.transform);
  // A 0.6 m cube turned 45 degrees about y is 0.6 * sqrt(2) wide in x.
  EXPECT_NEAR(bounds.max.x() - bounds.min.x(), 0.6 * std::sqrt(2.0), 1e-5);
  EXPECT_NEAR(bounds.max.y() - bounds.min.y(), 0.6, 1e-5);
}

TEST(WorldExtraction, SkipPredicateLeavesOutRopeProxies) {
  test::TestWorld world;
  // Rope collision proxies, tagged by the caller.
  for (int i = 0; i < 3; ++i) {
    btCollisionObject* proxy = world.add(std::make_unique<btCapsuleShapeX>(0.02, 0.1), btVector3(0.2 * i, 1, 0));
    proxy->setUserIndex(77);
  }
  ShapeMeshCache cache;
  Scene scene;
  ExtractionOptions options;
  options.skip = [](const btCollisionObject& object) { return object.getUserIndex() == 77; };
  extractWorld(world.world, cache, scene, options);
  EXPECT_EQ(scene.items.size(), world.objects.size() - 3);
}

TEST(WorldExtraction, ColourCallbackAndDefaultColours) {
  test::TestWorld world;
  ShapeMeshCache cache;
  Scene custom;
  ExtractionOptions options;
  options.colour = [](const btCollisionObject&) { return Rgb(0.1f, 0.2f, 0.3f); };
  extractWorld(world.world, cache, custom, options);
  for (const DrawItem& item : custom.items) EXPECT_TRUE(item.colour.isApprox(Rgb(0.1f, 0.2f, 0.3f)));

  // Default: the plane grey, static objects stone, a non-static object a palette colour.
  world.sphere->setCollisionFlags(world.sphere->getCollisionFlags() & ~btCollisionObject::CF_STATIC_OBJECT);
  EXPECT_TRUE(defaultObjectColour(*world.objects[0]).isApprox(Rgb(0.80f, 0.80f, 0.78f)));
  EXPECT_TRUE(defaultObjectColour(*world.box).isApprox(Rgb(0.74f, 0.70f, 0.62f)));
  const Rgb sphereColour = defaultObjectColour(*world.sphere);
  EXPECT_GT(sphereColour.maxCoeff() - sphereColour.minCoeff(), 0.1f);

  options.colour = [](const btCollisionObject&) { return Rgb(2.0f, 0.0f, 0.0f); };
  Scene bad;
  EXPECT_THROW(extractWorld(world.world, cache, bad, options), InvalidArgument);
  EXPECT_TRUE(bad.items.empty());  // nothing added on error
}

TEST(WorldExtraction, StaticShapesAreMeshedOnceAcrossFrames) {
  test::TestWorld world;
  ShapeMeshCache cache;
  for (int frame = 0; frame < 5; ++frame) {
    Scene scene;
    extractWorld(world.world, cache, scene);
    world.sphere->getWorldTransform().getOrigin() += btVector3(0.1, 0, 0);  // moving is free
  }
  EXPECT_EQ(cache.buildCount(), world.objects.size());
  EXPECT_EQ(cache.size(), world.objects.size());
}

TEST(WorldExtraction, ExplicitObjectListAndNullEntries) {
  test::TestWorld world;
  ShapeMeshCache cache;
  Scene scene;
  const btCollisionObject* objects[] = {world.box, world.sphere};
  extractObjects(objects, 2, cache, scene);
  EXPECT_EQ(scene.items.size(), 2u);
  const btCollisionObject* withNull[] = {world.box, nullptr};
  try {
    extractObjects(withNull, 2, cache, scene);
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.parameter(), "objects[1]");
  }
  EXPECT_EQ(scene.items.size(), 2u);  // unchanged
  extractObjects(std::vector<const btCollisionObject*>{world.sphere}, cache, scene);
  EXPECT_EQ(scene.items.size(), 3u);
}

}  // namespace
}  // namespace rope::render
