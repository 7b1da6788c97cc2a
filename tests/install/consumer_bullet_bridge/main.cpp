// SPDX-License-Identifier: MIT
// Uses SplineRope::bullet_bridge: a rope dropped onto a Bullet ground plane comes to rest on it.
// Bullet is the package's own precision (PkgConfig::BULLET).
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bullet_bridge/rope_world.h"

int main() {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher(&configuration);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
  world.setGravity(btVector3(0, -9.81, 0));
  btStaticPlaneShape planeShape(btVector3(0, 1, 0), 0);
  btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &planeShape));
  world.addRigidBody(&ground);

  int failures = 0;
  double lowest = 1.0, highest = -1.0;
  {
    rope::bullet::RopeWorld ropes(world);
    rope::RodSettings settings;
    settings.restLength = 1.0;
    settings.radius = 0.01;
    settings.massDamping = 1.0;
    rope::bullet::RopeObject cable(rope::Rod::fromSegment(settings, {-0.5, 0.3, 0}, {0.5, 0.3, 0}));
    ropes.addRope(cable);
    for (int i = 0; i < 2 * 60; ++i) {
      world.stepSimulation(1.0 / 60, 4, 1.0 / 240);
      for (const auto& record : ropes.lastReport().ropes) failures += record.ok ? 0 : 1;
    }
    for (int i = 0; i <= 100; ++i) {
      const double y = cable.rod().position(cable.rod().endParameter() * i / 100.0).y();
      lowest = std::min(lowest, y);
      highest = std::max(highest, y);
    }
    ropes.removeRope(cable);
  }
  world.removeRigidBody(&ground);

  // Lying on the plane: the whole centre line one radius above it, within a millimetre.
  std::printf("rope centre line between %.5f and %.5f m (radius 0.01 m), failed steps %d\n", lowest, highest,
              failures);
  const bool ok = failures == 0 && std::abs(lowest - 0.01) < 1e-3 && std::abs(highest - 0.01) < 1e-3;
  return ok ? 0 : 1;
}
