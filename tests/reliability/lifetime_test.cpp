// SPDX-License-Identifier: MIT
// Bodies that leave and objects destroyed in any order (issue 17, "Memory errors"). Freed memory is
// made inaccessible (test::Guarded), so a use after free stops these tests with SIGSEGV in a plain
// release build; the default test run also builds and runs this binary under AddressSanitizer
// (reliability.lifetime_under_asan), and the sanitize preset runs it with ASan and UBSan.
//   - a body attached to a rope, removed from the world and deleted, then a step (was: heap use after
//     free in RopeObject::beginSubstep);
//   - the Bullet world destroyed before the RopeWorld, before a rope, or before a KinematicRope's
//     removeFromWorld (was: segmentation fault);
//   - contactTest with a collision object that has no shape (was: segmentation fault);
//   - RopeWorld and RopeObject destroyed in either order leave nothing behind in the Bullet world.
#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <memory>

#include "bullet_bridge/kinematic_rope.h"
#include "bullet_bridge/rope_queries.h"
#include "bullet_bridge/rope_world.h"
#include "reliability/reliability_support.h"
#include "rope/common/error.h"
#include "rope/tractrix/tractrix_rope.h"

namespace rope::bullet {
namespace {

using test::ActionWorld;
using test::Guarded;

Rod straightRod(double y = 1.0) { return Rod::fromSegment(RodSettings{}, Vec3(0, y, 0), Vec3(1, y, 0)); }

btRigidBody::btRigidBodyConstructionInfo boxInfo(btCollisionShape& shape, double mass, const btVector3& origin) {
  btVector3 inertia(0, 0, 0);
  if (mass > 0) shape.calculateLocalInertia(btScalar(mass), inertia);
  btRigidBody::btRigidBodyConstructionInfo info(btScalar(mass), nullptr, &shape, inertia);
  info.m_startWorldTransform.setOrigin(origin);
  return info;
}

// Which build ran these tests (reliability.lifetime_under_asan looks for this line).
TEST(Lifetime, ReportsWhetherAddressSanitizerIsOn) {
#if defined(__SANITIZE_ADDRESS__)
  std::printf("lifetime tests: AddressSanitizer on\n");
#else
  std::printf("lifetime tests: AddressSanitizer off\n");
#endif
}

TEST(Lifetime, AttachedBodyRemovedAndDeletedIsDroppedWithoutTouchingIt) {
  ActionWorld world;
  RopeWorld ropes(world.world());
  btBoxShape shape(btVector3(0.05, 0.05, 0.05));
  Guarded<btRigidBody> box(boxInfo(shape, 1.0, btVector3(0, 1.05, 0)));
  world.world().addRigidBody(box.get());
  RopeObject rope(straightRod());
  ropes.addRope(rope);
  const int pin = rope.attachToPoint(1.0, btVector3(1, 1, 0));
  rope.attachToBody(0.0, *box, btVector3(0, -0.05, 0));
  world.step(3);
  ASSERT_EQ(rope.attachments().size(), 2u);

  world.world().removeRigidBody(box.get());
  box.destroy();  // any later access to the body faults
  ASSERT_NO_FATAL_FAILURE(world.step(1));
  EXPECT_TRUE(rope.lastStep().ok);
  EXPECT_EQ(rope.lastStep().droppedAttachments, 1);
  EXPECT_EQ(rope.warnings().droppedAttachments, 1);
  ASSERT_EQ(rope.attachments().size(), 1u);  // the pin stays
  EXPECT_EQ(rope.attachments()[0].id, pin);
  world.step(2);
  EXPECT_EQ(rope.lastStep().droppedAttachments, 0);
  EXPECT_EQ(rope.warnings().droppedAttachments, 1);
}

// A body whose index in the world changed is still found (and still attached); one that merely left
// the world is dropped like a deleted one.
TEST(Lifetime, AttachedBodyWhoseIndexChangedStaysAttached) {
  ActionWorld world(btVector3(0, 0, 0));
  RopeWorld ropes(world.world());
  RopeObject rope(straightRod());
  ropes.addRope(rope);
  btRigidBody* first = world.addBox(btVector3(0.05, 0.05, 0.05), 1.0, btVector3(5, 0, 0));
  world.addBox(btVector3(0.05, 0.05, 0.05), 1.0, btVector3(-5, 0, 0));
  btRigidBody* attached = world.addBox(btVector3(0.05, 0.05, 0.05), 1.0, btVector3(0, 1.05, 0));  // last
  rope.attachToBody(0.0, *attached, btVector3(0, -0.05, 0));
  const int indexBefore = attached->getWorldArrayIndex();
  world.deleteBody(first);  // Bullet moves the last object, the attached body, into its slot
  ASSERT_NE(attached->getWorldArrayIndex(), indexBefore);
  world.step(2);
  EXPECT_EQ(rope.attachments().size(), 1u);
  EXPECT_EQ(rope.warnings().droppedAttachments, 0);

  world.world().removeRigidBody(attached);  // left, not deleted: dropped all the same
  world.step(1);
  EXPECT_TRUE(rope.attachments().empty());
  EXPECT_EQ(rope.lastStep().droppedAttachments, 1);
  world.world().addRigidBody(attached);  // ActionWorld removes and deletes it
}

TEST(Lifetime, KinematicRopeFollowingADeletedBodyHolds) {
  ActionWorld world(btVector3(0, 0, 0));
  btBoxShape shape(btVector3(0.05, 0.05, 0.05));
  Guarded<btRigidBody> gripper(boxInfo(shape, 1.0, btVector3(0, 1, 0)));
  world.world().addRigidBody(gripper.get());
  gripper->setLinearVelocity(btVector3(-1, 0, 0));
  KinematicRope hose(TractrixRope(PointList{Vec3(0, 1, 0), Vec3(1, 1, 0)}, TractrixSettings{}));
  hose.addToWorld(world.world());
  hose.followBodyPoint(gripper.get(), btVector3(0, 0, 0));
  world.step(5);
  ASSERT_EQ(hose.lastStep().targetFailure, nullptr);
  const btVector3 held = hose.leadingEnd();
  world.world().removeRigidBody(gripper.get());
  gripper.destroy();
  ASSERT_NO_FATAL_FAILURE(world.step(3));
  EXPECT_NE(hose.lastStep().targetFailure, nullptr);
  EXPECT_EQ(hose.leadingEnd(), held);
  EXPECT_EQ(hose.warnings().targetFailures, 3);
  hose.removeFromWorld();
}

// The Bullet world's parts in the order Bullet's demos create them; the world itself in guarded
// memory, so touching it after its destruction faults.
struct GuardedBulletWorld {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  Guarded<btDiscreteDynamicsWorld> world{&dispatcher, &broadphase, &solver, &configuration};
  void step(int substeps) {
    for (int i = 0; i < substeps; ++i) world->stepSimulation(btScalar(1.0 / 240.0), 1, btScalar(1.0 / 240.0));
  }
};

TEST(Lifetime, BulletWorldDestroyedBeforeTheRopeWorld) {
  GuardedBulletWorld bullet;
  auto ropes = std::make_unique<RopeWorld>(*bullet.world);
  RopeObject rope(straightRod());
  RopeObject other(straightRod(2.0));
  ropes->addRope(rope);
  ropes->addRope(other);
  bullet.step(3);
  bullet.world.destroy();  // outside Bullet's rules (rope_world.h), but it must not crash
  EXPECT_NO_FATAL_FAILURE(ropes.reset());
  EXPECT_EQ(rope.world(), nullptr);
  rope.rod().step(1.0 / 240.0);  // the ropes live on as plain rods
}

TEST(Lifetime, BulletWorldDestroyedBeforeTheRopesAndThenTheRopeWorld) {
  GuardedBulletWorld bullet;
  RopeWorld ropes(*bullet.world);
  auto rope = std::make_unique<RopeObject>(straightRod());
  ropes.addRope(*rope);
  bullet.step(2);
  bullet.world.destroy();
  EXPECT_NO_FATAL_FAILURE(rope.reset());  // the rope leaves the RopeWorld, which learns the world is gone
  // ~RopeWorld at the end of the test must leave the dead world alone too.
}

TEST(Lifetime, BulletWorldDestroyedBeforeKinematicRopeRemoval) {
  GuardedBulletWorld bullet;
  KinematicRope hose(TractrixRope(PointList{Vec3(0, 1, 0), Vec3(1, 1, 0)}, TractrixSettings{}));
  hose.addToWorld(*bullet.world);
  hose.setTarget(btVector3(-1, 1, 0));
  bullet.step(2);
  bullet.world.destroy();
  EXPECT_NO_FATAL_FAILURE(hose.removeFromWorld());
  EXPECT_EQ(hose.world(), nullptr);
  // The rope can join a new world.
  ActionWorld fresh;
  hose.addToWorld(fresh.world());
  fresh.step(1);
  EXPECT_EQ(hose.lastStep().failure, nullptr);
  hose.removeFromWorld();
}

// Either order of destroying RopeWorld and RopeObject leaves the Bullet world exactly as before the
// ropes came: no collision object, no overlapping pair, no action of theirs, and it steps on.
TEST(Lifetime, RopeWorldAndRopeDestroyedInEitherOrderLeaveNothingBehind) {
  for (const bool ropeFirst : {true, false}) {
    ActionWorld world;
    world.addBox(btVector3(1, 0.1, 1), 0.0, btVector3(0, 0, 0));
    const int objects = world.world().getNumCollisionObjects();
    const int actions = world.actionCount();
    auto ropes = std::make_unique<RopeWorld>(world.world());
    auto rope = std::make_unique<RopeObject>(straightRod(0.12));
    ropes->addRope(*rope);
    auto piece = rope->cut(0.5);  // a second rope in the world, made by the first
    world.step(5);
    ASSERT_GT(world.world().getNumCollisionObjects(), objects);
    ASSERT_EQ(world.actionCount(), actions + 1);
    if (ropeFirst) {
      rope.reset();
      piece.reset();
      ropes.reset();
    } else {
      ropes.reset();
      EXPECT_EQ(rope->world(), nullptr);
      EXPECT_EQ(piece->world(), nullptr);
      piece.reset();
      rope.reset();
    }
    EXPECT_EQ(world.world().getNumCollisionObjects(), objects) << ropeFirst;
    EXPECT_EQ(world.actionCount(), actions);
    world.step(2);  // the pair cache is rebuilt from what is left: no rope capsule anywhere
    btBroadphasePairArray& pairs = world.world().getPairCache()->getOverlappingPairArray();
    for (int i = 0; i < pairs.size(); ++i) {
      for (const btBroadphaseProxy* proxy : {pairs[i].m_pProxy0, pairs[i].m_pProxy1}) {
        const auto* object = static_cast<const btCollisionObject*>(proxy->m_clientObject);
        EXPECT_EQ(CapsuleProxies::ropeOf(*object), nullptr);
      }
    }
  }
}

TEST(Lifetime, ContactTestWithShapelessObjectIsRefused) {
  ActionWorld world;
  RopeWorld ropes(world.world());
  RopeObject rope(straightRod());
  ropes.addRope(rope);
  btCollisionObject shapeless;
  try {
    contactTest(ropes, shapeless, 0.0);
    FAIL() << "no exception";
  } catch (const InvalidArgument& error) {
    EXPECT_EQ(error.parameter(), "object.shape");
  }
  btSphereShape sphere(btScalar(0.1));
  btCollisionObject broken;
  broken.setCollisionShape(&sphere);
  broken.getWorldTransform().setOrigin(btVector3(btScalar(std::numeric_limits<double>::quiet_NaN()), 1, 0));
  try {
    contactTest(ropes, broken, 0.0);
    FAIL() << "no exception";
  } catch (const InvalidArgument& error) {
    EXPECT_EQ(error.parameter(), "object.transform.origin.x");
  }
}

}  // namespace
}  // namespace rope::bullet
