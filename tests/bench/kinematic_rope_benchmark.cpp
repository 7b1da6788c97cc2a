// SPDX-License-Identifier: MIT
// Cost of a kinematic tractrix rope in a Bullet world (bullet_bridge/kinematic_rope.h), per
// stepSimulation of one 1/240 s substep: a 2 m rope whose leading end circles at 1 m/s (radius 0.8 m)
// through a field of 100 free boxes (5 cm, 0.2 m apart, no gravity, damped so that the field stays
// put), which it pushes. Variants: TRX_SD_MRG (6 initial sides, 4 capsules per span) and TRX with 20
// segments (one capsule each); "none" is the same world without a rope (Bullet's own cost), and
// "empty" is the rope alone in an empty world (tractrix pass, capsules, broadphase query). The counter
// rope_action_us is the rope's own action alone; the rest of a step is Bullet's, which grows with a
// rope because the pushed boxes then collide with each other.

#include <benchmark/benchmark.h>
#include <btBulletDynamicsCommon.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <vector>

#include "bullet_bridge/kinematic_rope.h"
#include "demos/scenes/bullet_world.h"

namespace {

using rope::PointList;
using rope::TractrixRope;
using rope::TractrixSettings;
using rope::TractrixVariant;
using rope::Vec3;
using rope::bullet::KinematicRope;

constexpr double kStep = 1.0 / 240.0;

// Actions run in the order they were added: one before and one after the rope's time its action.
struct Stopwatch {
  std::chrono::steady_clock::time_point start;
  double seconds = 0.0;
};
struct StartAction : btActionInterface {
  Stopwatch* watch;
  explicit StartAction(Stopwatch* w) : watch(w) {}
  void updateAction(btCollisionWorld*, btScalar) override { watch->start = std::chrono::steady_clock::now(); }
  void debugDraw(btIDebugDraw*) override {}
};
struct StopAction : btActionInterface {
  Stopwatch* watch;
  explicit StopAction(Stopwatch* w) : watch(w) {}
  void updateAction(btCollisionWorld*, btScalar) override {
    watch->seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - watch->start).count();
  }
  void debugDraw(btIDebugDraw*) override {}
};

struct World : rope::demos::BulletWorld {
  btBoxShape boxShape{btVector3(btScalar(0.025), btScalar(0.025), btScalar(0.025))};
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::unique_ptr<KinematicRope> rope;
  Stopwatch watch;
  StartAction startAction{&watch};
  StopAction stopAction{&watch};

  explicit World(bool boxes) : BulletWorld(btVector3(0, 0, 0)) {
    if (!boxes) return;
    btVector3 inertia(0, 0, 0);
    boxShape.calculateLocalInertia(btScalar(0.2), inertia);
    for (int i = 0; i < 10; ++i) {
      for (int k = 0; k < 10; ++k) {
        btRigidBody::btRigidBodyConstructionInfo info(btScalar(0.2), nullptr, &boxShape, inertia);
        info.m_startWorldTransform.setIdentity();
        info.m_startWorldTransform.setOrigin(btVector3(btScalar(-0.9 + 0.2 * i), 0, btScalar(-0.9 + 0.2 * k)));
        info.m_linearDamping = btScalar(0.9);
        info.m_angularDamping = btScalar(0.9);
        bodies.push_back(std::make_unique<btRigidBody>(info));
        bodies.back()->setActivationState(DISABLE_DEACTIVATION);
        world.addRigidBody(bodies.back().get());
      }
    }
  }
  ~World() {
    if (rope) {
      world.removeAction(&startAction);
      world.removeAction(&stopAction);
    }
    rope.reset();
    for (auto& body : bodies) world.removeRigidBody(body.get());
  }
  void addRope(TractrixVariant variant) {
    TractrixSettings settings;
    settings.variant = variant;
    settings.segmentCount = variant == TractrixVariant::kPolyline ? 20 : 6;
    // 2 m along -x from the circle's start point, tangent to the circle there.
    rope = std::make_unique<KinematicRope>(TractrixRope(PointList{Vec3(0, 0, -0.8), Vec3(-2, 0, -0.8)}, settings));
    world.addAction(&startAction);
    rope->addToWorld(world);
    world.addAction(&stopAction);
    rope->followPath([](double t) {
      const double angle = t / 0.8;  // 1 m/s on a 0.8 m circle
      return btVector3(static_cast<btScalar>(0.8 * std::sin(angle)), 0, static_cast<btScalar>(-0.8 * std::cos(angle)));
    });
  }
};

void run(benchmark::State& state, World& w) {
  // One lap first, so that the rope has bent, adapted and met the field.
  for (int i = 0; i < 1200; ++i) w.world.stepSimulation(static_cast<btScalar>(kStep), 1, static_cast<btScalar>(kStep));
  long contacts = 0;
  w.watch.seconds = 0.0;
  for (auto _ : state) {
    w.world.stepSimulation(static_cast<btScalar>(kStep), 1, static_cast<btScalar>(kStep));
    if (w.rope) contacts += static_cast<long>(w.rope->lastStep().contacts.size());
  }
  state.counters["contacts_per_substep"] =
      benchmark::Counter(static_cast<double>(contacts) / static_cast<double>(state.iterations()));
  if (w.rope) state.counters["capsules"] = w.rope->capsuleCount();
  // Wall time of the rope's own action per substep (tractrix, capsules, broadphase query, pushes).
  if (w.rope) state.counters["rope_action_us"] = benchmark::Counter(1e6 * w.watch.seconds / static_cast<double>(state.iterations()));
}

void BM_KinematicRopeSplineInBoxField(benchmark::State& state) {
  World w(true);
  w.addRope(TractrixVariant::kSplineSubdivideMerge);
  run(state, w);
}
BENCHMARK(BM_KinematicRopeSplineInBoxField)->Unit(benchmark::kMicrosecond);

void BM_KinematicRopePolylineInBoxField(benchmark::State& state) {
  World w(true);
  w.addRope(TractrixVariant::kPolyline);
  run(state, w);
}
BENCHMARK(BM_KinematicRopePolylineInBoxField)->Unit(benchmark::kMicrosecond);

void BM_BoxFieldWithoutRope(benchmark::State& state) {
  World w(true);
  run(state, w);
}
BENCHMARK(BM_BoxFieldWithoutRope)->Unit(benchmark::kMicrosecond);

void BM_KinematicRopeSplineEmptyWorld(benchmark::State& state) {
  World w(false);
  w.addRope(TractrixVariant::kSplineSubdivideMerge);
  run(state, w);
}
BENCHMARK(BM_KinematicRopeSplineEmptyWorld)->Unit(benchmark::kMicrosecond);

}  // namespace
