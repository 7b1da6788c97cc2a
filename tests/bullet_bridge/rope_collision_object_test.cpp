// SPDX-License-Identifier: MIT
// The rope as one Bullet collision object (capsule_proxies.h, collision_object/rope_dispatch.h): Bullet's own
// rayTest, convexSweepTest and contactTest hit the rope's capsules at the analytic surface and
// ropeHit gives s; group/mask filtering per rope; one object per rope, and adding and removing ropes
// leaves Bullet's object count and pair cache as they were; bad input is refused.
#include <gtest/gtest.h>

#include <BulletCollision/BroadphaseCollision/btOverlappingPairCache.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "bullet_bridge/detail/bullet_math.h"
#include "bullet_bridge/rope_queries.h"
#include "bullet_query_test_support.h"
#include "bullet_bridge/rope_world.h"
#include "demos/scenes/drape_scene.h"
#include "demos/scenes/physics_world.h"
#include "rope/common/error.h"

namespace rope::bullet {
namespace {

constexpr double kSurfaceTolerance = 1e-6;  // m, issue 14

RodSettings straightRod() {
  RodSettings rod = demos::DrapeSceneSettings::defaultRod();  // radius 1 cm
  rod.restLength = 1.0;
  return rod;
}

// Distance of p from the surface of the rope's capsule `capsule` (analytic: segment distance - r).
double surfaceGap(const RopeObject& rope, int capsule, const btVector3& p) {
  const Capsule c = rope.proxies().capsule(capsule);
  const btVector3 axis = c.b - c.a;
  const double t = std::clamp(static_cast<double>((p - c.a).dot(axis) / axis.length2()), 0.0, 1.0);
  return static_cast<double>((p - c.axisPoint(static_cast<btScalar>(t))).length() - c.radius);
}

// The child index Bullet reports with a ray hit.
struct ChildRayCallback : btCollisionWorld::ClosestRayResultCallback {
  using ClosestRayResultCallback::ClosestRayResultCallback;
  btScalar addSingleResult(btCollisionWorld::LocalRayResult& result, bool normalInWorldSpace) override {
    child = result.m_localShapeInfo != nullptr ? result.m_localShapeInfo->m_triangleIndex : -1;
    return ClosestRayResultCallback::addSingleResult(result, normalInWorldSpace);
  }
  int child = -2;
};

class RopeCollisionObject : public ::testing::Test {
 protected:
  RopeCollisionObject() : physics_(btVector3(0, 0, 0)) {
    rope_ = std::make_unique<RopeObject>(Rod::fromSegment(straightRod(), Vec3(0, 1, 0), Vec3(1, 1, 0)));
    physics_.ropes().addRope(*rope_);
  }
  // Capsule length in s (the straight rope's s is x).
  double capsuleLength() const { return rope_->proxies().proxy(0).s1 - rope_->proxies().proxy(0).s0; }
  demos::PhysicsWorld physics_;
  std::unique_ptr<RopeObject> rope_;
};

// Bullet's rayTest reaches each capsule child through processAllTriangles with its ray callback, where
// the rope's capsule shape answers in closed form (collision_object/rope_shape.h): the hit is on the
// analytic surface to 1e-6 m, as rope::bullet::rayTest's. (As btCapsuleShape children, Bullet's
// subsimplex convex cast put it 3e-6 to 4e-4 m off a 1 cm capsule, measured.)
constexpr double kBulletRayCastTolerance = kSurfaceTolerance;  // m

TEST_F(RopeCollisionObject, BulletRayTestHitsTheRopeAndRayTestIsExact) {
  const double radius = rope_->rod().settings().radius;
  for (const double x : {0.137, 0.5, 0.861}) {
    const double z = 0.004;  // off the top: the hit is where the ray enters the cylinder
    const btVector3 from(x, 2, z), to(x, 0, z);
    const double analyticY = 1.0 + std::sqrt(radius * radius - z * z);
    ChildRayCallback ray(from, to);
    physics_.world().rayTest(from, to, ray);
    ASSERT_TRUE(ray.hasHit()) << x;
    ASSERT_EQ(ray.m_collisionObject, &rope_->collisionObject());
    const btVector3 p = ray.m_hitPointWorld;
    EXPECT_NEAR(static_cast<double>(p.y()), analyticY, kBulletRayCastTolerance) << x;
    EXPECT_NEAR(static_cast<double>(ray.m_closestHitFraction), (2.0 - analyticY) / 2.0, kBulletRayCastTolerance / 2.0);
    const btVector3 analyticNormal = btVector3(0, static_cast<btScalar>(analyticY - 1), static_cast<btScalar>(z)) / radius;
    EXPECT_GT(static_cast<double>(ray.m_hitNormalWorld.dot(analyticNormal)), 1.0 - 1e-9) << x;
    ASSERT_GE(ray.child, 0);
    EXPECT_LT(std::abs(surfaceGap(*rope_, ray.child, p)), kBulletRayCastTolerance);
    // s from the child index and from the point alone: within one capsule of the truth.
    const auto byChild = ropeHit(*ray.m_collisionObject, ray.child, p);
    const auto byPoint = ropeHit(*ray.m_collisionObject, p);
    ASSERT_TRUE(byChild.has_value());
    ASSERT_TRUE(byPoint.has_value());
    EXPECT_EQ(byChild->rope, rope_.get());
    EXPECT_EQ(byPoint->capsule, ray.child);
    EXPECT_LE(std::abs(byChild->s - x), capsuleLength());
    EXPECT_LE(std::abs(byPoint->s - x), capsuleLength());
    // The convenience: the analytic surface to 1e-6 m, the normal and s exact.
    const auto exact = rayTest(physics_.ropes(), from, to);
    ASSERT_TRUE(exact.has_value());
    EXPECT_EQ(exact->rope, rope_.get());
    EXPECT_NEAR(static_cast<double>(exact->point.y()), analyticY, kSurfaceTolerance);
    EXPECT_NEAR(exact->s, x, kSurfaceTolerance);  // straight rope: s is x
    const btVector3 normal = btVector3(0, static_cast<btScalar>(analyticY - 1), static_cast<btScalar>(z)) / radius;
    EXPECT_GT(static_cast<double>(exact->normal.dot(normal)), 1.0 - 1e-9);
  }
}

// On a bent rope, from every side: Bullet's rayTest and rope::bullet::rayTest find the same capsule
// and point (both exact: rope_shape.h, ray_capsule.h), on the capsule's analytic surface.
TEST(RopeCollisionObjectWorld, BulletRayTestOnABentRopeMatchesTheExactQuery) {
  demos::PhysicsWorld physics(btVector3(0, 0, 0));
  PointList arc;
  for (int i = 0; i <= 12; ++i) {
    const double angle = 0.5 * 3.14159265358979323846 * i / 12;
    arc.emplace_back(0.3 * std::cos(angle), 1.0 + 0.3 * std::sin(angle), 0.05 * std::sin(3 * angle));
  }
  RopeObject rope(Rod::fromPolyline(straightRod(), arc, Rod::RestShape::kAsGiven));
  physics.ropes().addRope(rope);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), along(0.0, 1.0);
  int hits = 0;
  for (int i = 0; i < 200; ++i) {
    const Rod& rod = rope.rod();
    const double s = rod.beginParameter() + along(random) * (rod.endParameter() - rod.beginParameter());
    const Vec3 aim = rod.position(s) + 0.012 * Vec3(unit(random), unit(random), unit(random));
    Vec3 direction(unit(random), unit(random), unit(random));
    direction.normalize();
    const btVector3 from = toBullet(aim - 0.5 * direction), to = toBullet(aim + 0.5 * direction);
    ChildRayCallback bulletRay(from, to);
    physics.world().rayTest(from, to, bulletRay);
    const auto exact = rayTest(physics.ropes(), from, to);
    ASSERT_EQ(bulletRay.hasHit(), exact.has_value()) << i;
    if (!exact) continue;
    ++hits;
    EXPECT_LT(static_cast<double>((bulletRay.m_hitPointWorld - exact->point).length()), 1e-9) << i;
    EXPECT_LT(std::abs(surfaceGap(rope, bulletRay.child, bulletRay.m_hitPointWorld)), kSurfaceTolerance) << i;
    EXPECT_GT(static_cast<double>(bulletRay.m_hitNormalWorld.dot(exact->normal)), 1.0 - 1e-9) << i;
  }
  EXPECT_GT(hits, 100);
}

// Bullet's contactPairTest between two crossing ropes: both capsule children stand in as Bullet's
// btCapsuleShape (rope_dispatch.h), so the overlap is the capsules' to Bullet's GJK/EPA precision.
TEST(RopeCollisionObjectWorld, BulletContactPairTestBetweenTwoRopes) {
  demos::PhysicsWorld physics(btVector3(0, 0, 0));
  const double radius = straightRod().radius, overlap = 0.005;
  RopeObject first(Rod::fromSegment(straightRod(), Vec3(0, 1, 0), Vec3(1, 1, 0)));
  RopeObject second(Rod::fromSegment(straightRod(), Vec3(0.5, 1 + 2 * radius - overlap, -0.5),
                                     Vec3(0.5, 1 + 2 * radius - overlap, 0.5)));
  physics.ropes().addRope(first);
  physics.ropes().addRope(second);
  test::DeepestContact result;
  // Bullet's contactPairTest takes non-const objects; it only reads them.
  physics.world().contactPairTest(const_cast<btCollisionObject*>(&first.collisionObject()),
                                  const_cast<btCollisionObject*>(&second.collisionObject()), result);
  ASSERT_GT(result.count, 0);
  EXPECT_NEAR(result.distance, -overlap, kSurfaceTolerance);
}

TEST_F(RopeCollisionObject, BulletConvexSweepTestHitsTheRope) {
  const double radius = rope_->rod().settings().radius;
  btSphereShape ball(btScalar(0.02));
  btTransform from, to;
  from.setIdentity();
  to.setIdentity();
  from.setOrigin(btVector3(0.42, 2, 0));
  to.setOrigin(btVector3(0.42, 0, 0));
  btCollisionWorld::ClosestConvexResultCallback sweep(from.getOrigin(), to.getOrigin());
  physics_.world().convexSweepTest(&ball, from, to, sweep);
  ASSERT_TRUE(sweep.hasHit());
  ASSERT_EQ(sweep.m_hitCollisionObject, &rope_->collisionObject());
  // The ball touches the rope's top when its centre is at 1 + r + 0.02.
  const double expectedFraction = (2.0 - (1.0 + radius + 0.02)) / 2.0;
  EXPECT_NEAR(static_cast<double>(sweep.m_closestHitFraction), expectedFraction, kSurfaceTolerance / 2.0);
  EXPECT_NEAR(static_cast<double>(sweep.m_hitPointWorld.y()), 1.0 + radius, kSurfaceTolerance);
  const auto hit = ropeHit(*sweep.m_hitCollisionObject, sweep.m_hitPointWorld);
  ASSERT_TRUE(hit.has_value());
  EXPECT_LE(std::abs(hit->s - 0.42), capsuleLength());
}

TEST_F(RopeCollisionObject, BulletContactTestReportsTheRopeAndItsCapsule) {
  const double radius = rope_->rod().settings().radius;
  btBoxShape boxShape(btVector3(0.05, 0.05, 0.05));
  btCollisionObject box;
  box.setCollisionShape(&boxShape);
  box.getWorldTransform().setIdentity();
  const double depth = 0.002;
  box.getWorldTransform().setOrigin(btVector3(0.63, btScalar(1.0 + radius + 0.05 - depth), 0));
  struct Result : btCollisionWorld::ContactResultCallback {
    btScalar addSingleResult(btManifoldPoint& point, const btCollisionObjectWrapper* a, int, int indexA,
                             const btCollisionObjectWrapper* b, int, int indexB) override {
      const bool ropeIsA = a->getCollisionObject() != box;
      ++count;
      if (static_cast<double>(point.getDistance()) >= distance) return 0;  // keep the deepest point
      rope = ropeIsA ? a->getCollisionObject() : b->getCollisionObject();
      child = ropeIsA ? indexA : indexB;
      onRope = ropeIsA ? point.getPositionWorldOnA() : point.getPositionWorldOnB();
      distance = static_cast<double>(point.getDistance());
      return 0;
    }
    const btCollisionObject* box = nullptr;
    const btCollisionObject* rope = nullptr;
    int child = -1, count = 0;
    btVector3 onRope{0, 0, 0};
    double distance = std::numeric_limits<double>::infinity();
  } result;
  result.box = &box;
  physics_.world().contactTest(&box, result);
  ASSERT_GT(result.count, 0);
  EXPECT_EQ(result.rope, &rope_->collisionObject());
  EXPECT_NEAR(result.distance, -depth, kSurfaceTolerance);
  ASSERT_GE(result.child, 0);
  EXPECT_LT(std::abs(surfaceGap(*rope_, result.child, result.onRope)), kSurfaceTolerance);
  const auto hit = ropeHit(*result.rope, result.child, result.onRope);
  ASSERT_TRUE(hit.has_value());
  EXPECT_LE(std::abs(hit->s - 0.63), 0.05 + capsuleLength());  // under the box's 10 cm face
}

TEST_F(RopeCollisionObject, GroupAndMaskFilterPerRope) {
  const btVector3 from(0.5, 2, 0), to(0.5, 0, 0);
  const auto hits = [&](int mask) {
    btCollisionWorld::ClosestRayResultCallback ray(from, to);
    ray.m_collisionFilterMask = mask;
    physics_.world().rayTest(from, to, ray);
    return ray.hasHit();
  };
  const int group = rope_->settings().collisionGroup;
  EXPECT_TRUE(hits(group));
  EXPECT_FALSE(hits(~group));
  rope_->setCollisionFilter(1 << 12, -1);
  EXPECT_EQ(rope_->settings().collisionGroup, 1 << 12);
  EXPECT_FALSE(hits(group));
  EXPECT_TRUE(hits(1 << 12));
  // A mask that excludes the bodies' group: a box dropped on the rope falls through it.
  btRigidBody* box = physics_.addBox(btVector3(0.05, 0.05, 0.05), 1.0, btVector3(0.5, 1.2, 0));
  box->setLinearVelocity(btVector3(0, -1, 0));  // the world has no gravity
  rope_->setCollisionFilter(1 << 12, ~box->getBroadphaseHandle()->m_collisionFilterGroup);
  for (int i = 0; i < 240; ++i) physics_.world().stepSimulation(btScalar(1.0 / 240.0), 1, btScalar(1.0 / 240.0));
  EXPECT_TRUE(rope_->contacts().empty());
  EXPECT_LT(static_cast<double>(box->getWorldTransform().getOrigin().y()), 1.0);
}

TEST(RopeCollisionObjectWorld, OneObjectPerRopeAndRemovalRestoresThePairCache) {
  demos::PhysicsWorld physics;
  physics.addGround(0.0);
  physics.addBox(btVector3(0.1, 0.1, 0.1), 1.0, btVector3(0.3, 0.1, 0.3));
  for (int i = 0; i < 30; ++i) physics.world().stepSimulation(btScalar(1.0 / 240.0), 1, btScalar(1.0 / 240.0));
  const int objects = physics.world().getNumCollisionObjects();
  const int pairs = physics.world().getPairCache()->getNumOverlappingPairs();
  const int manifolds = physics.world().getDispatcher()->getNumManifolds();
  std::vector<std::unique_ptr<RopeObject>> ropes;
  for (int i = 0; i < 5; ++i) {
    const double z = 0.05 * i;
    ropes.push_back(std::make_unique<RopeObject>(Rod::fromSegment(straightRod(), Vec3(0, 0.011, z), Vec3(1, 0.011, z))));
    physics.ropes().addRope(*ropes.back());
  }
  EXPECT_EQ(physics.world().getNumCollisionObjects(), objects + 5);
  for (int i = 0; i < 30; ++i) physics.world().stepSimulation(btScalar(1.0 / 240.0), 1, btScalar(1.0 / 240.0));
  // The ropes lie on the ground and touch each other's boxes; Bullet made no manifold for them.
  EXPECT_GT(physics.world().getPairCache()->getNumOverlappingPairs(), pairs);
  for (int m = 0; m < physics.world().getDispatcher()->getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = physics.world().getDispatcher()->getManifoldByIndexInternal(m);
    EXPECT_EQ(CapsuleProxies::ropeOf(*manifold->getBody0()), nullptr);
    EXPECT_EQ(CapsuleProxies::ropeOf(*manifold->getBody1()), nullptr);
  }
  EXPECT_FALSE(ropes[0]->contacts().empty());  // the bridge saw the ground through the dispatch
  for (auto& rope : ropes) physics.ropes().removeRope(*rope);
  EXPECT_EQ(physics.world().getNumCollisionObjects(), objects);
  EXPECT_EQ(physics.world().getPairCache()->getNumOverlappingPairs(), pairs);
  EXPECT_EQ(physics.world().getDispatcher()->getNumManifolds(), manifolds);
}

TEST(RopeCollisionObjectWorld, BadInputThrowsAndChangesNothing) {
  demos::PhysicsWorld physics(btVector3(0, 0, 0));
  RopeObject rope(Rod::fromSegment(straightRod(), Vec3(0, 1, 0), Vec3(1, 1, 0)));
  physics.ropes().addRope(rope);
  // A second RopeWorld on the same Bullet world.
  try {
    RopeWorld second(physics.world());
    ADD_FAILURE() << "a second RopeWorld was accepted";
  } catch (const InvalidArgument& error) {
    EXPECT_EQ(error.parameter(), "world");
  }
  // The rope, already in a world, added to a second one.
  demos::PhysicsWorld other(btVector3(0, 0, 0));
  const int otherObjects = other.world().getNumCollisionObjects();
  try {
    other.ropes().addRope(rope);
    ADD_FAILURE() << "a rope joined a second world";
  } catch (const InvalidArgument& error) {
    EXPECT_EQ(error.parameter(), "rope");
  }
  EXPECT_EQ(other.world().getNumCollisionObjects(), otherObjects);
  EXPECT_EQ(rope.world(), &physics.ropes());
  // A query with NaN endpoints, a NaN hit point, a child index that is no capsule.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  try {
    rayTest(physics.ropes(), btVector3(nan, 0, 0), btVector3(0, 0, 0));
    ADD_FAILURE();
  } catch (const InvalidArgument& error) {
    EXPECT_EQ(error.parameter(), "from.x");
  }
  try {
    rayTestRopes(physics.ropes(), btVector3(0, 0, 0), btVector3(0, nan, 0));
    ADD_FAILURE();
  } catch (const InvalidArgument& error) {
    EXPECT_EQ(error.parameter(), "to.y");
  }
  try {
    ropeHit(rope.collisionObject(), btVector3(0, 0, nan));
    ADD_FAILURE();
  } catch (const InvalidArgument& error) {
    EXPECT_EQ(error.parameter(), "point.z");
  }
  try {
    ropeHit(rope.collisionObject(), rope.proxies().size(), btVector3(0, 1, 0));
    ADD_FAILURE();
  } catch (const InvalidArgument& error) {
    EXPECT_EQ(error.parameter(), "childIndex");
  }
  // A group/mask change while the world steps (from the substep callback), and a group of 0.
  const int group = rope.settings().collisionGroup, mask = rope.settings().collisionMask;
  int refused = 0;
  physics.ropes().setSubstepCallback([&](const ContactReport&) {
    try {
      rope.setCollisionFilter(1 << 13, 1);
    } catch (const InvalidArgument& error) {
      if (error.parameter() == "rope") ++refused;
    }
  });
  physics.world().stepSimulation(btScalar(1.0 / 240.0), 1, btScalar(1.0 / 240.0));
  EXPECT_EQ(refused, 1);
  EXPECT_EQ(physics.ropes().warnings().callbackExceptions, 0);
  physics.ropes().setSubstepCallback({});
  try {
    rope.setCollisionFilter(0, -1);
    ADD_FAILURE();
  } catch (const InvalidArgument& error) {
    EXPECT_EQ(error.parameter(), "group");
  }
  EXPECT_EQ(rope.settings().collisionGroup, group);
  EXPECT_EQ(rope.settings().collisionMask, mask);
  EXPECT_EQ(rope.collisionObject().getBroadphaseHandle()->m_collisionFilterGroup, group);
  EXPECT_EQ(rope.collisionObject().getBroadphaseHandle()->m_collisionFilterMask, mask);
}

TEST(RopeCollisionObjectWorld, DispatcherIsRestoredAndUserCompoundsStillCollide) {
  demos::PhysicsWorld physics;
  physics.addGround(0.0);
  // A compound body resting on the ground: its pair goes to Bullet's own compound algorithm.
  auto compound = std::make_unique<btCompoundShape>();
  btTransform local;
  local.setIdentity();
  static btBoxShape child(btVector3(0.1, 0.1, 0.1));
  compound->addChildShape(local, &child);
  btTransform start;
  start.setIdentity();
  start.setOrigin(btVector3(2, 0.5, 2));
  btRigidBody* body = physics.addBody(std::move(compound), 1.0, start);
  for (int i = 0; i < 480; ++i) physics.world().stepSimulation(btScalar(1.0 / 240.0), 1, btScalar(1.0 / 240.0));
  EXPECT_NEAR(static_cast<double>(body->getWorldTransform().getOrigin().y()), 0.1, 0.01);
}

}  // namespace
}  // namespace rope::bullet
