// SPDX-License-Identifier: MIT
#pragma once
// A stock Bullet world for the rope scenes (and the tests and benchmarks that build them): the
// pipeline of bullet_world.h with a RopeWorld on top. Owns every body it creates; the ropes are
// owned by the scenes.

#include <btBulletDynamicsCommon.h>

#include <memory>
#include <string>
#include <vector>

#include "bullet_bridge/rope_world.h"
#include "demos/scenes/bullet_world.h"
#include "demos/scenes/demo_scene.h"
#include "render/scene.h"
#include "render/shape_mesh_cache.h"
#include "rope/common/types.h"

namespace rope::demos {

class PhysicsWorld {
 public:
  explicit PhysicsWorld(const btVector3& gravity = btVector3(0, btScalar(-9.81), 0));
  ~PhysicsWorld();
  PhysicsWorld(const PhysicsWorld&) = delete;
  PhysicsWorld& operator=(const PhysicsWorld&) = delete;

  btDiscreteDynamicsWorld& world() { return bullet_->world; }
  const btDiscreteDynamicsWorld& world() const { return bullet_->world; }
  bullet::RopeWorld& ropes() { return *ropes_; }
  const bullet::RopeWorld& ropes() const { return *ropes_; }

  // A box of the given half extents (m) at `origin`; mass 0 makes it static. Friction 0.5.
  btRigidBody* addBox(const btVector3& halfExtents, double mass, const btTransform& transform);
  btRigidBody* addBox(const btVector3& halfExtents, double mass, const btVector3& origin);
  // The static ground plane y = height.
  btRigidBody* addGround(double height = 0.0);
  // A body of any shape (the world keeps the shape); mass 0 makes it static. Friction 0.5.
  btRigidBody* addBody(std::unique_ptr<btCollisionShape> shape, double mass, const btTransform& transform);
  // A static triangle mesh (btBvhTriangleMeshShape over `mesh`, which the world keeps). Friction 0.5.
  btRigidBody* addStaticMesh(std::unique_ptr<btTriangleMesh> mesh, const btTransform& transform);

  // Draws the rigid bodies (planes as the ground), leaving out the ropes' capsules (dynamic and kinematic).
  void draw(render::Scene& scene) const;

 private:
  std::unique_ptr<BulletWorld> bullet_;
  std::unique_ptr<bullet::RopeWorld> ropes_;
  std::vector<std::unique_ptr<btTriangleMesh>> triangleMeshes_;  // before shapes_: the mesh shapes point into them
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  mutable render::ShapeMeshCache meshes_;
};

// The scenes' conversions at the Bullet boundary (btScalar is float or double, per the Bullet build).
inline btVector3 toBullet(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()), static_cast<btScalar>(v.z()));
}
inline Vec3 toVec3(const btVector3& v) {
  return Vec3(static_cast<double>(v.x()), static_cast<double>(v.y()), static_cast<double>(v.z()));
}

// Advances the world by one fixed step h (s) and checks every rope of its RopeWorld: throws
// std::runtime_error starting with `scene` if a rope's step or the coupled rope-rope solve failed.
// Returns the knots the ropes' adaptivity inserted and removed in that step (the other fields unset).
StepMeasurements stepAndCheck(PhysicsWorld& physics, double h, const std::string& scene);

// What every rope scene measures of a rope: control points, strain, its deepest penetration into
// bodies and the deepest rope-rope overlap of the world's last substep.
StepMeasurements ropeMeasurements(const PhysicsWorld& physics, const bullet::RopeObject& rope);

// A rope's drawing style in the Bullet scenes: the tube of the rope's radius, spans in alternating
// colours, and optionally its control polygon as a thin overlay (as [A]'s knot-tying figure shows it,
// so the adaptivity is visible).
void drawRope(render::Scene& scene, const bullet::RopeObject& rope, bool showControlPolygon = false);

}  // namespace rope::demos
