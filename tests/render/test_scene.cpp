// SPDX-License-Identifier: MIT
#include "test_scene.h"

#include "render/rope_drawing.h"
#include "render/world_extraction.h"

namespace rope::render::test {

TestWorld::TestWorld() {
  add(std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), 0.0), btVector3(0, 0, 0));
  box = add(std::make_unique<btBoxShape>(btVector3(0.3, 0.3, 0.3)), btVector3(-0.6, 0.3, 0.0));
  sphere = add(std::make_unique<btSphereShape>(0.3), btVector3(0.45, 0.3, -0.75));
  add(std::make_unique<btCapsuleShape>(0.15, 0.5), btVector3(1.0, 0.4, 0.45), btQuaternion(btVector3(0, 0, 1), 1.2));
  add(std::make_unique<btCylinderShapeZ>(btVector3(0.25, 0.25, 0.3)), btVector3(-1.6, 0.25, -0.7));
  add(std::make_unique<btConeShape>(0.3, 0.7), btVector3(1.7, 0.35, -0.5));
}

TestWorld::~TestWorld() {
  for (auto& object : objects) world.removeCollisionObject(object.get());
}

btCollisionObject* TestWorld::add(std::unique_ptr<btCollisionShape> shape, const btVector3& origin,
                                  const btQuaternion& rotation) {
  auto object = std::make_unique<btCollisionObject>();
  object->setCollisionShape(shape.get());
  object->setWorldTransform(btTransform(rotation, origin));
  world.addCollisionObject(object.get());
  shapes.push_back(std::move(shape));
  objects.push_back(std::move(object));
  return objects.back().get();
}

KnotVector ropeKnots() { return KnotVector::clampedUniform(3, 8, 0.0, 1.0); }

PointList ropePoints() {
  return {Vec3(-2.1, 0.04, 0.7),  Vec3(-1.5, 0.04, 0.55), Vec3(-1.1, 0.5, 0.25), Vec3(-0.75, 0.68, 0.05),
          Vec3(-0.35, 0.68, -0.05), Vec3(0.0, 0.3, 0.2),  Vec3(0.35, 0.04, 0.9),  Vec3(1.2, 0.04, 1.1)};
}

Scene buildScene(TestWorld& world, ShapeMeshCache& cache, bool annotated) {
  Scene scene;
  ExtractionOptions options;
  options.colour = [&world](const btCollisionObject& object) {
    if (object.getCollisionShape()->getShapeType() == STATIC_PLANE_PROXYTYPE) return Rgb(0.80f, 0.80f, 0.78f);
    // Palette by index, also for these static objects (the default draws statics grey).
    // Blue box, so that the orange rope on it is easy to tell apart.
    const Rgb palette[] = {Rgb(0.36f, 0.55f, 0.78f), Rgb(0.45f, 0.70f, 0.45f), Rgb(0.62f, 0.46f, 0.75f),
                           Rgb(0.35f, 0.72f, 0.72f), Rgb(0.84f, 0.38f, 0.33f)};
    return palette[static_cast<std::size_t>(object.getWorldArrayIndex() + 4) % 5];
  };
  extractWorld(world.world, cache, scene, options);
  RopeStyle style;
  style.tube.radius = kRopeRadius;
  style.tube.alternateSpanColours = annotated;
  style.showControlPolygon = annotated;
  addRope(scene, ropeKnots(), ropePoints(), style);
  return scene;
}

}  // namespace rope::render::test
