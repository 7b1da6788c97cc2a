// SPDX-License-Identifier: MIT
#pragma once
// The renderer's reference scene for tests and the benchmark: a ground plane with a box, sphere,
// capsule, cylinder and cone, and a cubic B-spline rope draped over the box. Y is up, metres.

#include <btBulletCollisionCommon.h>

#include <memory>
#include <vector>

#include "render/scene.h"
#include "render/shape_mesh_cache.h"
#include "rope/common/types.h"
#include "rope/spline/knot_vector.h"

namespace rope::render::test {

struct TestWorld {
  TestWorld();
  ~TestWorld();
  TestWorld(const TestWorld&) = delete;
  TestWorld& operator=(const TestWorld&) = delete;

  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btCollisionWorld world{&dispatcher, &broadphase, &configuration};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btCollisionObject>> objects;

  btCollisionObject* box = nullptr;  // half extents 0.3, centre (-0.6, 0.3, 0)
  btCollisionObject* sphere = nullptr;

  btCollisionObject* add(std::unique_ptr<btCollisionShape> shape, const btVector3& origin,
                         const btQuaternion& rotation = btQuaternion::getIdentity());
};

// The rope: cubic, clamped, over the box top (y = 0.6) with radius kRopeRadius.
constexpr double kRopeRadius = 0.04;
KnotVector ropeKnots();
PointList ropePoints();

// Extracts the world and adds the rope (alternating span colours and the control polygon when
// annotated is true).
Scene buildScene(TestWorld& world, ShapeMeshCache& cache, bool annotated = false);

}  // namespace rope::render::test
