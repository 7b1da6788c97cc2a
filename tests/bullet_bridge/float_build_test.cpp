// Scenario test that builds in both Bullet precisions (it needs no scene builders, so the float
// build of tests/bullet_bridge/float_build_check.cmake compiles only the rope and the bridge): a rope
// dropped onto a box comes to rest on it, a rope hitting a free box conserves momentum (to btScalar
// round-off: Bullet keeps the box's velocity in btScalar), and a rope dropped across another one on
// the box comes to rest on it (rope-rope contact through the same broadphase).
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "bullet_bridge/rope_world.h"

namespace rope::bullet {
namespace {

constexpr double kStep = 1.0 / 240.0;

struct World {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration};
  btBoxShape boxShape{btVector3(btScalar(0.6), btScalar(0.1), btScalar(0.3))};
  std::unique_ptr<btRigidBody> box;

  World(double gravity, double mass) {
    world.setGravity(btVector3(0, static_cast<btScalar>(-gravity), 0));
    btVector3 inertia(0, 0, 0);
    if (mass > 0) boxShape.calculateLocalInertia(static_cast<btScalar>(mass), inertia);
    btRigidBody::btRigidBodyConstructionInfo info(static_cast<btScalar>(mass), nullptr, &boxShape, inertia);
    info.m_startWorldTransform.setIdentity();
    info.m_startWorldTransform.setOrigin(btVector3(0, btScalar(0.1), 0));
    box = std::make_unique<btRigidBody>(info);
    box->setActivationState(DISABLE_DEACTIVATION);
    world.addRigidBody(box.get());
  }
  ~World() { world.removeRigidBody(box.get()); }
};

RodSettings rope(bool gravity) {
  RodSettings rod;
  rod.radius = 0.01;
  rod.youngsModulus = 2.0e8;
  rod.bendingStiffness = 1.0e-3;
  rod.massDamping = gravity ? 0.2 : 0.0;
  rod.maxControlPoints = 48;
  rod.restLength = 1.0;
  if (!gravity) {
    rod.gravity = Vec3::Zero();
    rod.adaptive = false;  // knot removal changes the rope's momentum (see rope_world_test.cpp)
  }
  return rod;
}

TEST(FloatBuildScenario, RopeDroppedOntoBoxComesToRest) {
  World w(9.81, 0.0);
  RopeWorld ropes(w.world);
  RopeObject object(Rod::fromSegment(rope(true), Vec3(-0.5, 0.3, 0), Vec3(0.5, 0.3, 0)));
  ropes.addRope(object);
  double resting = 0.0;
  for (int i = 0; i < 720; ++i) {
    w.world.stepSimulation(btScalar(kStep), 1, btScalar(kStep));
    ASSERT_TRUE(object.lastStep().ok);
    if (i >= 480) resting = std::max(resting, object.lastStep().maxPenetration);
  }
  EXPECT_LT(resting, 0.001);
  const Rod& rod = object.rod();
  for (int i = 0; i <= 20; ++i) {
    const double s = rod.beginParameter() + (rod.endParameter() - rod.beginParameter()) * i / 20.0;
    EXPECT_NEAR(rod.position(std::min(s, rod.endParameter())).y(), 0.21, 0.001);
  }
  std::printf("btScalar %zu bytes: resting penetration %.3g m\n", sizeof(btScalar), resting);
}

TEST(FloatBuildScenario, RopeAndFreeBoxConserveMomentum) {
  World w(0.0, 2.0);
  RopeWorld ropes(w.world);
  RopeObject object(Rod::fromSegment(rope(false), Vec3(-0.5, 0.5, 0), Vec3(0.5, 0.5, 0)));
  object.rod().setVelocities(PointList(static_cast<std::size_t>(object.rod().controlPointCount()), Vec3(0, -3, 0)));
  ropes.addRope(object);
  auto total = [&]() -> Vec3 {
    const btVector3 v = w.box->getLinearVelocity();
    return object.rod().momentum() + 2.0 * Vec3(v.x(), v.y(), v.z());
  };
  const Vec3 initial = total();
  double worst = 0.0;
  for (int i = 0; i < 240; ++i) {
    w.world.stepSimulation(btScalar(kStep), 1, btScalar(kStep));
    worst = std::max(worst, (total() - initial).norm() / initial.norm());
  }
  EXPECT_LT(w.box->getLinearVelocity().y(), -0.1);  // the rope pushed it
  // Exact in double; float Bullet rounds the box's velocity to ~1e-7 relative per impulse.
  EXPECT_LT(worst, sizeof(btScalar) == sizeof(double) ? 1e-9 : 1e-4);
  std::printf("btScalar %zu bytes: momentum drift %.3g\n", sizeof(btScalar), worst);
}

TEST(FloatBuildScenario, RopeDroppedAcrossAnotherRestsOnIt) {
  World w(9.81, 0.0);
  RopeWorld ropes(w.world);
  const double r = rope(true).radius;
  RopeObject lower(Rod::fromSegment(rope(true), Vec3(-0.5, 0.2 + r, 0), Vec3(0.5, 0.2 + r, 0)));
  RopeObject upper(Rod::fromSegment(rope(true), Vec3(0, 0.3, -0.5), Vec3(0, 0.3, 0.5)));
  ropes.addRope(lower);
  ropes.addRope(upper);
  double worst = 0.0;
  int touching = 0;
  for (int i = 0; i < 480; ++i) {
    w.world.stepSimulation(btScalar(kStep), 1, btScalar(kStep));
    ASSERT_TRUE(lower.lastStep().ok && upper.lastStep().ok);
    worst = std::max(worst, ropes.lastReport().maxSelfOverlap());
    touching += upper.lastStep().ropeContacts > 0 ? 1 : 0;
  }
  EXPECT_LT(worst, 0.2 * 2.0 * r);
  EXPECT_GT(touching, 100);
  // Resting across the lower rope: its middle one diameter above the lower rope's centre line.
  const Rod& rod = upper.rod();
  EXPECT_NEAR(rod.position(0.5 * (rod.beginParameter() + rod.endParameter())).y(), 0.2 + 3.0 * r, 0.15 * 2.0 * r);
  std::printf("btScalar %zu bytes: rope-rope overlap %.3g m\n", sizeof(btScalar), worst);
}

}  // namespace
}  // namespace rope::bullet
