// SPDX-License-Identifier: MIT
// Cost of ropes in a Bullet world (bullet_bridge/rope_world.h), per stepSimulation of one 1/240 s
// substep: one 64-control-point rope draped over a field of 100 static boxes, and N ropes resting on
// a ground plane (N = 1, 10, 100) to show how the cost grows. Counters split each step into Bullet's
// own work (broadphase, its narrowphase and solver for the rigid bodies: the step minus the rope
// action), the pair-cache scan, our narrowphase + contact law, the rod solve, the proxy update and
// rope-rope contact (capsule pairs of the ropes themselves, which now share the broadphase).

#include <benchmark/benchmark.h>
#include <btBulletDynamicsCommon.h>

#include <chrono>
#include <memory>
#include <vector>

#include "bullet_bridge/rope_world.h"
#include "demos/scenes/bullet_world.h"

namespace {

using rope::Rod;
using rope::RodSettings;
using rope::Vec3;
using rope::bullet::ContactReport;
using rope::bullet::RopeObject;
using rope::bullet::RopeStepRecord;
using rope::bullet::RopeWorld;

constexpr double kStep = 1.0 / 240.0;

// The stock pipeline (demos/scenes/bullet_world.h) with a RopeWorld, static bodies and ropes.
struct World : rope::demos::BulletWorld {
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::unique_ptr<RopeWorld> ropes;
  std::vector<std::unique_ptr<RopeObject>> ropeObjects;

  World() : BulletWorld(btVector3(0, btScalar(-9.81), 0)) { ropes = std::make_unique<RopeWorld>(world); }
  ~World() {
    ropes.reset();
    for (auto& body : bodies) world.removeRigidBody(body.get());
  }
  void addStatic(std::unique_ptr<btCollisionShape> shape, const btVector3& origin) {
    btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, shape.get());
    info.m_startWorldTransform.setIdentity();
    info.m_startWorldTransform.setOrigin(origin);
    shapes.push_back(std::move(shape));
    bodies.push_back(std::make_unique<btRigidBody>(info));
    world.addRigidBody(bodies.back().get());
  }
};

RodSettings ropeSettings(int controlPoints, double length) {
  RodSettings rod;
  rod.radius = 0.01;
  rod.youngsModulus = 2.0e8;
  rod.bendingStiffness = 1.0e-3;
  rod.massDamping = 0.2;
  rod.restLength = length;
  rod.initialControlPoints = controlPoints;
  rod.minControlPoints = controlPoints;  // keep the size the benchmark names
  // No cap on resolution: maxControlPoints stays the default (128), whatever the contacts ask for.
  return rod;
}

// Steps the world `state` times, reporting per-step shares as counters (ms per step).
void runSteps(benchmark::State& state, World& w) {
  double bridge = 0.0, scan = 0.0, contact = 0.0, solve = 0.0, proxy = 0.0, ropeRope = 0.0;
  long contacts = 0;
  w.ropes->setSubstepCallback([&](const ContactReport& report) {
    scan += report.pairScanSeconds;
    ropeRope += report.ropeContactSeconds;
    for (const RopeStepRecord& rope : report.ropes) {
      contact += rope.contactSeconds;
      solve += rope.solveSeconds;
      proxy += rope.proxySeconds;
      contacts += rope.contacts;
    }
  });
  double total = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    w.world.stepSimulation(btScalar(kStep), 1, btScalar(kStep));
    total += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  bridge = scan + contact + solve + proxy + ropeRope;
  const double n = static_cast<double>(state.iterations());
  state.counters["ms_step"] = 1e3 * total / n;
  // Everything outside the bridge's own timers: Bullet's step, but also the report's assembly, the
  // prefetch hints and per-rope bookkeeping in RopeWorld::substep (with 100 ropes on a plane 1.7 ms,
  // of which Bullet's own code was 0.4 % of the step in a profile).
  state.counters["ms_rest"] = 1e3 * (total - bridge) / n;
  state.counters["ms_pair_scan"] = 1e3 * scan / n;
  state.counters["ms_narrowphase"] = 1e3 * contact / n;
  state.counters["ms_rod_solve"] = 1e3 * solve / n;
  state.counters["ms_proxies"] = 1e3 * proxy / n;
  state.counters["ms_rope_rope"] = 1e3 * ropeRope / n;
  state.counters["contacts"] = static_cast<double>(contacts) / n;
  w.ropes->setSubstepCallback(nullptr);
}

// One 64-control-point, 3 m rope settled over a 10 x 10 field of 0.1 m boxes 0.3 m apart.
void BM_RopeOverBoxField(benchmark::State& state) {
  World w;
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      w.addStatic(std::make_unique<btBoxShape>(btVector3(0.05, 0.05, 0.05)),
                  btVector3(btScalar(-1.35 + 0.3 * i), btScalar(0.05), btScalar(-1.35 + 0.3 * j)));
    }
  }
  w.addStatic(std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), 0), btVector3(0, 0, 0));
  w.ropeObjects.push_back(std::make_unique<RopeObject>(
      Rod::fromSegment(ropeSettings(64, 3.0), Vec3(-1.5, 0.3, -0.05), Vec3(1.5, 0.3, 0.05))));
  w.ropes->addRope(*w.ropeObjects.back());
  for (int i = 0; i < 240; ++i) w.world.stepSimulation(btScalar(kStep), 1, btScalar(kStep));  // settle
  runSteps(state, w);
  state.counters["control_points"] = w.ropeObjects.back()->rod().controlPointCount();
}
BENCHMARK(BM_RopeOverBoxField)->Unit(benchmark::kMillisecond);

// N ropes (1 m, 16 control points) resting side by side on a ground plane; with range(1) == 0 the
// ropes leave each other out of the broadphase (collisionMask without the rope group: no rope-rope or
// self-contact), which shows what rope-rope pairs in Bullet's broadphase cost.
void BM_RopesOnGround(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  rope::bullet::BulletRopeSettings bridge;
  if (state.range(1) == 0) bridge.collisionMask = ~bridge.collisionGroup;
  World w;
  w.addStatic(std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), 0), btVector3(0, 0, 0));
  for (int i = 0; i < count; ++i) {
    const double z = 0.05 * (i - 0.5 * count);
    w.ropeObjects.push_back(std::make_unique<RopeObject>(
        Rod::fromSegment(ropeSettings(16, 1.0), Vec3(-0.5, 0.0105, z), Vec3(0.5, 0.0105, z)), bridge));
    w.ropes->addRope(*w.ropeObjects.back());
  }
  for (int i = 0; i < 120; ++i) w.world.stepSimulation(btScalar(kStep), 1, btScalar(kStep));  // settle
  runSteps(state, w);
  state.counters["ropes"] = count;
}
BENCHMARK(BM_RopesOnGround)
    ->ArgsProduct({{1, 10, 100}, {1, 0}})
    ->ArgNames({"ropes", "rope_rope"})
    ->Unit(benchmark::kMillisecond);

}  // namespace
