// SPDX-License-Identifier: MIT
// World queries that see ropes (bullet_bridge/rope_queries.h): rays and contact tests return the rope
// and the curve parameter s, through the capsules' broadphase proxies.
#include "bullet_bridge/rope_queries.h"

#include <gtest/gtest.h>

#include <limits>

#include "bullet_bridge/rope_world.h"
#include "demos/scenes/drape_scene.h"
#include "demos/scenes/physics_world.h"
#include "rope/common/error.h"

namespace rope::bullet {
namespace {

// Geometry goes through btScalar: exact to 1e-9 m in the double build, to float round-off otherwise.
constexpr double kTolerance = sizeof(btScalar) == sizeof(double) ? 1e-9 : 1e-6;

class RopeQueries : public ::testing::Test {
 protected:
  RopeQueries() : physics_(btVector3(0, 0, 0)) {
    RodSettings rod = demos::DrapeSceneSettings::defaultRod();  // radius 1 cm
    rod.restLength = 1.0;
    rope_ = std::make_unique<RopeObject>(Rod::fromSegment(rod, Vec3(0, 1, 0), Vec3(1, 1, 0)));
    physics_.ropes().addRope(*rope_);
  }
  demos::PhysicsWorld physics_;
  std::unique_ptr<RopeObject> rope_;
};

TEST_F(RopeQueries, RayHitsRopeAtItsParameter) {
  const auto hit = rayTestRopes(physics_.ropes(), btVector3(0.3, 2, 0), btVector3(0.3, 0, 0));
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->rope, rope_.get());
  EXPECT_EQ(hit->body, nullptr);
  EXPECT_NEAR(hit->s, 0.3, kTolerance);  // the rope is straight: s is x
  EXPECT_NEAR(hit->point.y(), 1.01, kTolerance);
  EXPECT_NEAR(hit->fraction, 0.99 / 2.0, kTolerance);
  EXPECT_NEAR(hit->normal.y(), 1.0, kTolerance);
  // Along the rope's axis direction from beyond its end: the end cap.
  const auto cap = rayTestRopes(physics_.ropes(), btVector3(2, 1, 0), btVector3(0.5, 1, 0));
  ASSERT_TRUE(cap.has_value());
  EXPECT_NEAR(cap->s, 1.0, kTolerance);
  EXPECT_NEAR(cap->point.x(), 1.01, kTolerance);
}

TEST_F(RopeQueries, RayMissesBesideTheRope) {
  EXPECT_FALSE(rayTestRopes(physics_.ropes(), btVector3(0.3, 2, 0.05), btVector3(0.3, 0, 0.05)).has_value());
  EXPECT_FALSE(rayTestRopes(physics_.ropes(), btVector3(0.3, 2, 0), btVector3(0.3, 1.5, 0)).has_value());
}

TEST_F(RopeQueries, WorldRayReturnsClosestOfBodiesAndRopes) {
  btRigidBody* box = physics_.addBox(btVector3(0.1, 0.1, 0.1), 0.0, btVector3(0.3, 0.5, 0));
  const auto fromAbove = rayTest(physics_.ropes(), btVector3(0.3, 2, 0), btVector3(0.3, 0, 0));
  ASSERT_TRUE(fromAbove.has_value());
  EXPECT_EQ(fromAbove->rope, rope_.get());
  const auto fromBelow = rayTest(physics_.ropes(), btVector3(0.3, 0, 0), btVector3(0.3, 2, 0));
  ASSERT_TRUE(fromBelow.has_value());
  EXPECT_EQ(fromBelow->body, box);
  EXPECT_EQ(fromBelow->rope, nullptr);
  EXPECT_NEAR(fromBelow->point.y(), 0.4, 1e-6);
}

TEST_F(RopeQueries, ContactTestReturnsRopeAndParameter) {
  btSphereShape sphere(0.05);
  btCollisionObject probe;
  probe.setCollisionShape(&sphere);
  probe.getWorldTransform().setOrigin(btVector3(0.7, 1.05, 0));
  const std::vector<RopeContactHit> hits = contactTest(physics_.ropes(), probe);
  ASSERT_FALSE(hits.empty());
  // Every capsule the sphere overlaps reports its own closest point; the deepest is at s = 0.7.
  const RopeContactHit* deepest = &hits.front();
  for (const RopeContactHit& hit : hits) {
    EXPECT_EQ(hit.rope, rope_.get());
    EXPECT_NEAR(hit.s, 0.7, 0.06);
    if (hit.contact.distance < deepest->contact.distance) deepest = &hit;
  }
  EXPECT_NEAR(deepest->s, 0.7, 1e-6);
  EXPECT_NEAR(deepest->contact.distance, -0.01, 1e-6);
  probe.getWorldTransform().setOrigin(btVector3(0.7, 1.2, 0));
  EXPECT_TRUE(contactTest(physics_.ropes(), probe).empty());
  EXPECT_FALSE(contactTest(physics_.ropes(), probe, 0.2).empty());  // speculative up to the margin
}

TEST_F(RopeQueries, RemovedRopeIsNotFound) {
  physics_.ropes().removeRope(*rope_);
  EXPECT_FALSE(rayTestRopes(physics_.ropes(), btVector3(0.3, 2, 0), btVector3(0.3, 0, 0)).has_value());
}

TEST_F(RopeQueries, BadInputThrows) {
  const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
  EXPECT_THROW(rayTestRopes(physics_.ropes(), btVector3(nan, 0, 0), btVector3(0, 0, 0)), InvalidArgument);
  EXPECT_THROW(rayTest(physics_.ropes(), btVector3(0, 0, 0), btVector3(0, nan, 0)), InvalidArgument);
  btSphereShape sphere(0.05);
  btCollisionObject probe;
  probe.setCollisionShape(&sphere);
  EXPECT_THROW(contactTest(physics_.ropes(), probe, -1.0), InvalidArgument);
}

}  // namespace
}  // namespace rope::bullet
