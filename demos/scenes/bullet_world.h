// SPDX-License-Identifier: MIT
#pragma once
// The stock Bullet dynamics pipeline every rope world here is built on: default collision
// configuration, dbvt broadphase, sequential-impulse solver and btDiscreteDynamicsWorld, made in the
// order Bullet's own demos make them (and destroyed in reverse). PhysicsWorld holds one; tests and
// benchmarks that link only the bridge hold one directly. Header only and Bullet only, so the float
// build (bullet_bridge_float_build_test) uses it without the scene library.

#include <btBulletDynamicsCommon.h>

namespace rope::demos {

struct BulletWorld {
  explicit BulletWorld(const btVector3& gravity) { world.setGravity(gravity); }
  BulletWorld(const BulletWorld&) = delete;
  BulletWorld& operator=(const BulletWorld&) = delete;

  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration};
};

}  // namespace rope::demos
