// SPDX-License-Identifier: MIT
// Capsule proxies (bullet_bridge/capsule_proxies.h): one collision object per rope whose compound
// children follow the knot vector, whose tree leaves cover each capsule now and at the predicted end
// of the step, and whose boxes Bullet would drop as too large are detected and reported instead.
#include "bullet_bridge/capsule_proxies.h"

#include <gtest/gtest.h>

#include <BulletCollision/BroadphaseCollision/btBroadphaseProxy.h>

#include <algorithm>
#include <functional>
#include <random>
#include <utility>
#include <vector>

#include "bullet_bridge/rope_world.h"
#include "demos/scenes/drape_scene.h"
#include "demos/scenes/physics_world.h"
#include "rope/common/error.h"

namespace rope::bullet {
namespace {

RodSettings straightRope() {
  RodSettings rod = demos::DrapeSceneSettings::defaultRod();
  rod.gravity = Vec3::Zero();
  rod.restLength = 1.0;
  rod.initialControlPoints = 8;  // 5 spans
  return rod;
}

bool contains(const btVector3& lo, const btVector3& hi, const btVector3& p, btScalar pad) {
  for (int i = 0; i < 3; ++i) {
    if (p[i] - pad < lo[i] || p[i] + pad > hi[i]) return false;
  }
  return true;
}

TEST(CapsuleProxies, CapsulesPerSpanFollowKnotInsertion) {
  demos::PhysicsWorld physics(btVector3(0, 0, 0));
  BulletRopeSettings settings;
  settings.capsulesPerSpan = 3;
  RopeObject rope(Rod::fromSegment(straightRope(), Vec3(0, 1, 0), Vec3(1, 1, 0)), settings);
  physics.ropes().addRope(rope);
  EXPECT_EQ(rope.proxies().size(), 3 * 5);
  const int objects = physics.world().getNumCollisionObjects();
  rope.rod().insertKnot(0.37);
  physics.world().stepSimulation(btScalar(1.0 / 240.0), 1, btScalar(1.0 / 240.0));
  const int spans = rope.rod().controlPointCount() - rope.rod().degree();
  EXPECT_EQ(rope.proxies().size(), 3 * spans);
  EXPECT_EQ(physics.world().getNumCollisionObjects(), objects);  // still one object for the rope
  EXPECT_EQ(rope.proxies().shape().getNumChildShapes(), rope.proxies().size());
  // The capsules tile the parameter range without gaps.
  for (int i = 0; i + 1 < rope.proxies().size(); ++i) {
    EXPECT_EQ(rope.proxies().proxy(i).s1, rope.proxies().proxy(i + 1).s0);
  }
  EXPECT_EQ(rope.proxies().proxy(0).s0, rope.rod().beginParameter());
  EXPECT_EQ(rope.proxies().proxy(rope.proxies().size() - 1).s1, rope.rod().endParameter());
}

TEST(CapsuleProxies, SweptBoxesCoverStartAndPredictedEnd) {
  demos::PhysicsWorld physics(btVector3(0, 0, 0));
  RopeObject rope(Rod::fromSegment(straightRope(), Vec3(0, 1, 0), Vec3(1, 1, 0)));
  rope.rod().setVelocities(PointList(static_cast<std::size_t>(rope.rod().controlPointCount()), Vec3(0, -24, 0)));
  physics.ropes().addRope(rope);
  const double h = 1.0 / 240.0;
  physics.world().stepSimulation(btScalar(h), 1, btScalar(h));
  const Rod& rod = rope.rod();
  const btScalar radius = static_cast<btScalar>(rod.settings().radius);
  const btBroadphaseProxy* handle = rope.collisionObject().getBroadphaseHandle();
  ASSERT_NE(handle, nullptr);
  std::vector<const btDbvtNode*> leaves(static_cast<std::size_t>(rope.proxies().size()), nullptr);
  struct Leaves : btDbvt::ICollide {
    void Process(const btDbvtNode* leaf) override { (*out)[static_cast<std::size_t>(leaf->dataAsInt)] = leaf; }
    std::vector<const btDbvtNode*>* out = nullptr;
  } collect;
  collect.out = &leaves;
  btDbvt::enumLeaves(rope.proxies().tree().m_root, collect);
  for (int i = 0; i < rope.proxies().size(); ++i) {
    const CapsuleProxy& proxy = rope.proxies().proxy(i);
    const btDbvtNode* leaf = leaves[static_cast<std::size_t>(i)];
    ASSERT_NE(leaf, nullptr);
    for (double s : {proxy.s0, proxy.s1}) {
      const Vec3 now = rod.position(s);
      const Vec3 next = now + h * rod.velocity(s);  // 10 cm lower
      for (const Vec3& p : {now, next}) {
        // The capsule's leaf, and the rope's broadphase box around all leaves.
        EXPECT_TRUE(contains(leaf->volume.Mins(), leaf->volume.Maxs(), btVector3(p.x(), p.y(), p.z()), radius));
        EXPECT_TRUE(contains(handle->m_aabbMin, handle->m_aabbMax, btVector3(p.x(), p.y(), p.z()), radius));
      }
    }
    EXPECT_EQ(proxy.object, &rope.collisionObject());
  }
  // Not found by Bullet's own narrowphase or solver.
  EXPECT_FALSE(rope.collisionObject().hasContactResponse());
  EXPECT_EQ(CapsuleProxies::ropeOf(rope.collisionObject()), &rope);
}

TEST(CapsuleProxies, EndSpeedsAreTheCurveSpeedsAtTheCapsuleEndsOfTheLastRebuild) {
  demos::PhysicsWorld physics(btVector3(0, 0, 0));
  RopeObject rope(Rod::fromSegment(straightRope(), Vec3(0, 1, 0), Vec3(1, 1, 0)));
  physics.ropes().addRope(rope);
  const double h = 1.0 / 240.0;
  // Two different motions, one per step: a spin about the rope's middle (speed grows along it), then
  // a slide along -y whose speed falls along it. The speeds must follow each step's rebuild.
  const Vec3 spin(0.0, 0.0, 3.0), middle(0.5, 1.0, 0.0);
  for (int motion = 0; motion < 2; ++motion) {
    Rod& rod = rope.rod();
    PointList velocities;
    for (const Vec3& p : rod.controlPoints()) {
      velocities.push_back(motion == 0 ? Vec3(spin.cross(p - middle)) : Vec3(0.0, -(2.0 - p.x()), 0.0));
    }
    rod.setVelocities(velocities);
    physics.world().stepSimulation(btScalar(h), 1, btScalar(h));
    const CapsuleProxies& proxies = rope.proxies();
    const std::vector<double>& speeds = proxies.endSpeeds(rope.rod());
    ASSERT_EQ(speeds.size(), static_cast<std::size_t>(proxies.size()) + 1);
    for (int i = 0; i <= proxies.size(); ++i) {
      const double s = i < proxies.size() ? proxies.proxy(i).s0 : proxies.proxy(i - 1).s1;
      EXPECT_EQ(speeds[static_cast<std::size_t>(i)], rope.rod().velocity(s).norm()) << "motion " << motion << ", end " << i;
    }
    // Asked again without a rebuild: the same values (the same vector).
    EXPECT_EQ(&proxies.endSpeeds(rope.rod()), &speeds);
  }
}

// The tree holds one leaf per capsule, each the box leafBoxes() mirrors (the self-contact walk reads
// the array, rope_world.cpp), and the end arclengths are the rest arclengths at the capsule ends,
// through refits, knot insertions (capsules added) and removals (capsules dropped).
TEST(CapsuleProxies, TreeLeavesAreTheLeafBoxesAndEndArcsFollowTheRestCurve) {
  demos::PhysicsWorld physics(btVector3(0, 0, 0));
  RopeObject rope(Rod::fromSegment(straightRope(), Vec3(0, 1, 0), Vec3(1, 1, 0)));
  physics.ropes().addRope(rope);
  const double h = 1.0 / 240.0;
  int internalNodes = 0, changes = 0;
  const auto check = [&](const char* when) {
    const CapsuleProxies& proxies = rope.proxies();
    // Each leaf once, holding its capsule's box as leafBoxes() has it.
    std::vector<int> seen(static_cast<std::size_t>(proxies.size()), 0);
    std::function<void(const btDbvtNode*)> visit = [&](const btDbvtNode* node) {
      if (node->isinternal()) {
        ++internalNodes;
        visit(node->childs[0]);
        visit(node->childs[1]);
        return;
      }
      ASSERT_GE(node->dataAsInt, 0) << when;
      ASSERT_LT(node->dataAsInt, proxies.size()) << when;
      ++seen[static_cast<std::size_t>(node->dataAsInt)];
      const btDbvtVolume& mirror = proxies.leafBoxes()[static_cast<std::size_t>(node->dataAsInt)];
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(node->volume.Mins()[k], mirror.Mins()[k]) << when << ", capsule " << node->dataAsInt;
        EXPECT_EQ(node->volume.Maxs()[k], mirror.Maxs()[k]) << when << ", capsule " << node->dataAsInt;
      }
    };
    ASSERT_EQ(proxies.leafBoxes().size(), static_cast<std::size_t>(proxies.size())) << when;
    const btDbvtNode* root = proxies.tree().m_root;
    ASSERT_NE(root, nullptr);
    visit(root);
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), proxies.size()) << when;
    // A rope made from a segment: its parameter is the rest arclength from its start.
    const std::vector<double>& arcs = proxies.endArcs(rope.rod());
    ASSERT_EQ(arcs.size(), static_cast<std::size_t>(proxies.size()) + 1) << when;
    for (int i = 0; i <= proxies.size(); ++i) {
      const double s = i < proxies.size() ? proxies.proxy(i).s0 : proxies.proxy(i - 1).s1;
      EXPECT_NEAR(arcs[static_cast<std::size_t>(i)], s - rope.rod().beginParameter(), 1e-12) << when << ", end " << i;
    }
    EXPECT_EQ(&proxies.endArcs(rope.rod()), &arcs);  // once per rebuild
  };
  check("at the start");
  // A bend that moves the leaves (the tree is refitted), then more capsules, then fewer.
  PointList velocities;
  for (const Vec3& p : rope.rod().controlPoints()) velocities.push_back(Vec3(0.0, 40.0 * (p.x() - 0.5) * (p.x() - 0.5), 0.0));
  rope.rod().setVelocities(velocities);
  for (int step = 0; step < 3; ++step) {
    physics.world().stepSimulation(btScalar(h), 1, btScalar(h));
    check("after a refit");
  }
  const int before = rope.proxies().size();
  for (const double s : {0.13, 0.37, 0.61, 0.83}) rope.rod().insertKnot(s);
  physics.world().stepSimulation(btScalar(h), 1, btScalar(h));
  check("after knot insertions");
  changes += rope.proxies().size() > before ? 1 : 0;
  const int inserted = rope.proxies().size();
  for (const double s : {0.37, 0.61}) rope.rod().removeKnot(s);
  physics.world().stepSimulation(btScalar(h), 1, btScalar(h));
  check("after knot removals");
  changes += rope.proxies().size() < inserted ? 1 : 0;
  EXPECT_EQ(changes, 2);  // capsules were added, then dropped
  EXPECT_GT(internalNodes, 0);
}

// A rebuild from the rod it was last rebuilt from keeps the capsules (and the end speeds); any change
// of the control points, the knots or the velocities in between is followed, as by a fresh object.
TEST(CapsuleProxies, ARebuildFollowsEveryChangeOfTheRodAndOnlyThen) {
  Rod rod = Rod::fromSegment(straightRope(), Vec3(0, 1, 0), Vec3(1, 1, 0));
  CapsuleProxies proxies(nullptr, kKinematicRopeTag, rod.settings().radius);
  const auto expectAsFresh = [&](const char* when) {
    CapsuleProxies fresh(nullptr, kKinematicRopeTag, rod.settings().radius);
    fresh.rebuild(rod);
    ASSERT_EQ(proxies.size(), fresh.size()) << when;
    for (int i = 0; i < fresh.size(); ++i) {
      EXPECT_EQ(proxies.proxy(i).s0, fresh.proxy(i).s0) << when << ", capsule " << i;
      EXPECT_EQ(proxies.capsule(i).a, fresh.capsule(i).a) << when << ", capsule " << i;
      EXPECT_EQ(proxies.capsule(i).b, fresh.capsule(i).b) << when << ", capsule " << i;
    }
    EXPECT_EQ(proxies.endSpeeds(rod), fresh.endSpeeds(rod)) << when;
    EXPECT_EQ(proxies.endArcs(rod), fresh.endArcs(rod)) << when;
  };
  proxies.rebuild(rod);
  expectAsFresh("first rebuild");
  const std::vector<double>* speeds = &proxies.endSpeeds(rod);
  proxies.rebuild(rod);  // nothing changed
  expectAsFresh("same rod");
  EXPECT_EQ(&proxies.endSpeeds(rod), speeds);
  PointList points = rod.controlPoints();
  points[3] += Vec3(0.0, 0.02, 0.0);
  rod.setControlPoints(points);
  proxies.rebuild(rod);
  expectAsFresh("a control point moved");
  PointList velocities(static_cast<std::size_t>(rod.controlPointCount()), Vec3(0.0, 0.0, 0.0));
  velocities[2] = Vec3(0.5, 0.0, 0.0);
  rod.setVelocities(velocities);
  proxies.rebuild(rod);
  expectAsFresh("new velocities, same curve");
  rod.insertKnot(0.41);  // the same curve, more capsules
  proxies.rebuild(rod);
  expectAsFresh("a knot inserted");
  // A winch: the end span's rest length changes, and endArcs must follow it.
  const std::vector<double> arcs = proxies.endArcs(rod);
  rod.payOut(Rod::End::kEnd, 0.05);
  proxies.rebuild(rod);
  expectAsFresh("an end paid out");
  EXPECT_NE(proxies.endArcs(rod).back(), arcs.back());
  rod.payOut(Rod::End::kEnd, -0.05);  // reeled in again: a negative length
  proxies.rebuild(rod);
  expectAsFresh("an end reeled in");
}

// The midphase query reports exactly the capsules whose leaves meet the box (a caller-fitted chain:
// no margin is added), in increasing order, for boxes that meet none, some and all of a folded chain:
// of 120 capsules (the query walks the tree) and of 40 (it scans the leaf boxes' array, which must
// hold each leaf's box as the tree does, also after capsules come and go).
TEST(CapsuleProxies, CapsulesOverlappingAreTheCapsulesWhoseLeavesMeetTheBox) {
  for (const int count : {120, 40}) {
    SCOPED_TRACE(testing::Message() << count << " capsules");
    CapsuleProxies proxies(nullptr, kKinematicRopeTag, 0.005);
    std::mt19937_64 random(20261205);
    std::uniform_real_distribution<double> step(-0.01, 0.01);
    std::vector<double> ends;
    std::vector<btVector3> axis;
    btVector3 point(0, 0, 0);
    for (int i = 0; i <= count; ++i) {
      ends.push_back(0.01 * i);
      axis.push_back(point);
      point += btVector3(static_cast<btScalar>(step(random)), static_cast<btScalar>(step(random)),
                         static_cast<btScalar>(step(random)));
    }
    // Built longer, cut back and grown again: leaves leave and join at the end.
    proxies.rebuild(ends, axis);
    proxies.rebuild(std::vector<double>(ends.begin(), ends.begin() + count / 2 + 1),
                    std::vector<btVector3>(axis.begin(), axis.begin() + count / 2 + 1));
    proxies.rebuild(ends, axis);
    const btVector3 pad(btScalar(0.005), btScalar(0.005), btScalar(0.005));
    for (int i = 0; i < proxies.size(); ++i) {
      btVector3 lo = axis[static_cast<std::size_t>(i)], hi = lo;
      lo.setMin(axis[static_cast<std::size_t>(i) + 1]);
      hi.setMax(axis[static_cast<std::size_t>(i) + 1]);
      ASSERT_TRUE(proxies.fitLeaf(i, lo - pad, hi + pad));
    }
    struct Leaves : btDbvt::ICollide {
      void Process(const btDbvtNode* leaf) override { out->push_back(leaf); }
      std::vector<const btDbvtNode*>* out = nullptr;
    } collect;
    std::vector<const btDbvtNode*> leafNodes;
    collect.out = &leafNodes;
    btDbvt::enumLeaves(proxies.tree().m_root, collect);
    ASSERT_EQ(leafNodes.size(), static_cast<std::size_t>(proxies.size()));
    ASSERT_EQ(proxies.leafBoxes().size(), leafNodes.size());
    for (const btDbvtNode* leaf : leafNodes) {
      const btDbvtVolume& box = proxies.leafBoxes()[static_cast<std::size_t>(leaf->dataAsInt)];
      for (int axisIndex = 0; axisIndex < 3; ++axisIndex) {
        EXPECT_EQ(box.Mins()[axisIndex], leaf->volume.Mins()[axisIndex]) << "leaf " << leaf->dataAsInt;
        EXPECT_EQ(box.Maxs()[axisIndex], leaf->volume.Maxs()[axisIndex]) << "leaf " << leaf->dataAsInt;
      }
    }
    std::uniform_real_distribution<double> centre(-0.06, 0.06), size(0.0, 0.04);
    std::vector<int> found;
    btNodeStack stack;
    std::size_t reported = 0, empty = 0;
    for (int query = 0; query < 200; ++query) {
      const btVector3 c(static_cast<btScalar>(centre(random)), static_cast<btScalar>(centre(random)),
                        static_cast<btScalar>(centre(random)));
      const btScalar half = static_cast<btScalar>(query == 0 ? 10.0 : size(random));
      const btVector3 lo = c - btVector3(half, half, half), hi = c + btVector3(half, half, half);
      proxies.capsulesOverlapping(lo, hi, found, stack);
      std::vector<int> expected;
      for (const btDbvtNode* leaf : leafNodes) {
        if (TestAabbAgainstAabb2(leaf->volume.Mins(), leaf->volume.Maxs(), lo, hi)) expected.push_back(leaf->dataAsInt);
      }
      std::sort(expected.begin(), expected.end());
      EXPECT_EQ(found, expected) << "query " << query;
      reported += found.size();
      empty += found.empty() ? 1 : 0;
    }
    // Not vacuous: some queries meet nothing, the first meets everything, most meet some.
    EXPECT_GT(empty, 0u);
    EXPECT_GT(reported, static_cast<std::size_t>(proxies.size()) + 200);
  }
}

TEST(CapsuleProxies, HugeBoxesAreReportedNotHandedToBullet) {
  demos::PhysicsWorld physics(btVector3(0, 0, 0));
  RopeObject rope(Rod::fromSegment(straightRope(), Vec3(0, 1, 0), Vec3(1, 1, 0)));
  physics.ropes().addRope(rope);
  physics.world().stepSimulation(btScalar(1.0 / 240.0), 1, btScalar(1.0 / 240.0));
  EXPECT_EQ(rope.lastStep().proxyOverflows, 0);
  // 1e9 m/s: the box would span 4e6 m, beyond Bullet's 1e6 m limit (it would disable the object).
  rope.rod().setVelocities(PointList(static_cast<std::size_t>(rope.rod().controlPointCount()), Vec3(1e9, 0, 0)));
  physics.world().stepSimulation(btScalar(1.0 / 240.0), 1, btScalar(1.0 / 240.0));
  EXPECT_EQ(rope.lastStep().proxyOverflows, rope.proxies().size());
  EXPECT_EQ(physics.ropes().lastReport().ropes.at(0).proxyOverflows, rope.proxies().size());
  EXPECT_NE(rope.collisionObject().getActivationState(), DISABLE_SIMULATION);
}

// A caller-built chain (the kinematic rope's path) refuses mismatched input naming it, and leaves the
// chain as it was; capsule indices out of range are refused too.
TEST(CapsuleProxies, CallerBuiltChainRefusesBadInputAndChangesNothing) {
  int owner = 0;
  CapsuleProxies chain(&owner, kKinematicRopeTag, 0.01);
  const std::vector<double> ends{0.0, 0.5, 1.0};
  const std::vector<btVector3> axis{btVector3(0, 0, 0), btVector3(0.5, 0, 0), btVector3(1, 0, 0)};
  chain.rebuild(ends, axis);
  ASSERT_EQ(chain.size(), 2);
  const auto expectNaming = [](const char* name, const std::function<void()>& call) {
    try {
      call();
      ADD_FAILURE() << "no exception for " << name;
    } catch (const InvalidArgument& error) {
      EXPECT_EQ(error.parameter(), name);
    }
  };
  expectNaming("ends", [&] { chain.rebuild({0.0}, {btVector3(0, 0, 0)}); });
  expectNaming("axis", [&] { chain.rebuild(ends, {btVector3(0, 0, 0), btVector3(1, 0, 0)}); });
  expectNaming("i", [&] { chain.placeCapsule(2); });
  expectNaming("i", [&] { chain.fitLeaf(-1, btVector3(0, 0, 0), btVector3(1, 1, 1)); });
  EXPECT_EQ(chain.size(), 2);
  EXPECT_EQ(chain.proxy(1).s0, 0.5);
  EXPECT_EQ(chain.capsule(1).b, btVector3(1, 0, 0));
  EXPECT_EQ(chain.object().getUserIndex2(), kKinematicRopeTag);
  EXPECT_EQ(CapsuleProxies::ropeOf(chain.object()), nullptr);
}

}  // namespace
}  // namespace rope::bullet
