// SPDX-License-Identifier: MIT
// Scenario tests of ropes as Bullet world objects (bullet_bridge/rope_world.h, rope_object.h):
// resting contact, a thin bar, a fast impact, Newton's third law, two-way coupling, substeps, bad input.
#include "bullet_bridge/rope_world.h"

#include <gtest/gtest.h>

#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <limits>
#include <thread>

#include "demos/scenes/capstan_scene.h"
#include "demos/scenes/drape_scene.h"
#include "demos/scenes/pile_scene.h"
#include "demos/scenes/physics_world.h"
#include "rope/common/error.h"

namespace rope::bullet {
namespace {

constexpr double kStep = 1.0 / 240.0;

RodSettings limpRope(double radius = 0.01) {
  RodSettings rod = demos::DrapeSceneSettings::defaultRod();
  rod.radius = radius;
  return rod;
}

void stepWorld(btDiscreteDynamicsWorld& world, int steps) {
  for (int i = 0; i < steps; ++i) world.stepSimulation(btScalar(kStep), 1, btScalar(kStep));
}

double lowestPoint(const Rod& rod) {
  double lowest = std::numeric_limits<double>::max();
  for (int i = 0; i <= 200; ++i) {
    const double s = rod.beginParameter() + (rod.endParameter() - rod.beginParameter()) * i / 200.0;
    lowest = std::min(lowest, rod.position(std::min(s, rod.endParameter())).y());
  }
  return lowest;
}

// A rope dropped 0.2 m onto a static box comes to rest on its top face, and no point of the rope's
// centre line ever goes below the top face.
TEST(RopeWorldScenario, RopeDroppedOntoBoxComesToRestOnIt) {
  demos::DrapeScene scene{demos::DrapeSceneSettings{}};
  const double radius = scene.rope().rod().settings().radius;
  double impactPenetration = 0.0;
  double restingPenetration = 0.0;
  double lowest = std::numeric_limits<double>::max();
  const int steps = static_cast<int>(std::lround(4.0 / kStep));
  for (int i = 0; i < steps; ++i) {
    const demos::StepMeasurements m = scene.step();
    impactPenetration = std::max(impactPenetration, *m.maxPenetration);
    if (i >= steps - 240) restingPenetration = std::max(restingPenetration, *m.maxPenetration);
    lowest = std::min(lowest, scene.lowestPoint());
  }
  // Measured: 1.77 um deep at rest (the README's 1.8 um), 24.6 um at impact, momentum 9e-16 kg m/s.
  EXPECT_LT(restingPenetration, 5e-6);
  EXPECT_LT(impactPenetration, 7.5e-5);
  EXPECT_GT(lowest, 0.2);  // the box's top face: the centre line never went through it
  EXPECT_NEAR(scene.lowestPoint(), 0.2 + radius, 5e-6);
  EXPECT_LT(scene.rope().rod().momentum().norm(), 1e-12);  // at rest
  EXPECT_GT(scene.rope().lastStep().contacts, 0);
  RecordProperty("resting_penetration_m", std::to_string(restingPenetration));
  RecordProperty("impact_penetration_m", std::to_string(impactPenetration));
  std::printf("drop on box: resting penetration %.3g m, impact %.3g m (radius %.3g m)\n", restingPenetration,
              impactPenetration, radius);
}

// Dropped from 1 m above it, the rope drapes over a 2 mm bar: both halves hang down and it is still
// there after 5 s.
TEST(RopeWorldScenario, RopeDrapesOverThinBarAndStays) {
  demos::DrapeScene scene{demos::DrapeSceneSettings::thinBar()};
  const int steps = static_cast<int>(std::lround(6.5 / kStep));
  const int landed = static_cast<int>(std::lround(1.5 / kStep));  // after the fall and the first swing
  double deepest = 0.0;
  double lowestTop = 10.0;  // the rope's highest point over the last 5 s: it must stay on the bar
  for (int i = 0; i < steps; ++i) {
    deepest = std::max(deepest, *scene.step().maxPenetration);
    if (i >= landed) lowestTop = std::min(lowestTop, scene.highestPoint());
  }
  EXPECT_GT(lowestTop, 1.0);  // never slid off the bar (top face at 1.0) in those 5 s
  const Rod& rod = scene.rope().rod();
  const double radius = rod.settings().radius;
  // Still on the bar: the highest point sits on it (measured 0.2 mm low), both ends hang below it.
  EXPECT_NEAR(scene.highestPoint(), 1.0 + radius, 0.06 * radius);
  EXPECT_LT(rod.position(rod.beginParameter()).y(), 0.8);
  EXPECT_LT(rod.position(rod.endParameter()).y(), 0.8);
  EXPECT_GT(scene.rope().lastStep().contacts, 0);
  // No tunnelling: measured 0.95 mm deep at worst, while landing (the README's figure; 0.82 mm undamped);
  // bound 2.1x.
  EXPECT_LT(deepest, 0.2 * radius);
  std::printf("thin bar: deepest penetration %.3g m, top %.4f m\n", deepest, scene.highestPoint());
}

// A rope moving at 20 m/s (8.3 cm per step, more than the plate and the rope together) hits a 1 cm
// plate and stays on the near side. Swept over speeds: a soft speculative law once passed at exactly
// 20 m/s and tunnelled at 17 m/s, so one speed proves little.
TEST(RopeWorldScenario, FastRopeDoesNotPassThroughThinPlate) {
  for (const double speed : {12.0, 17.0, 20.0, 23.0, 30.0, 40.0}) {
    demos::PhysicsWorld physics(btVector3(0, 0, 0));
    physics.addBox(btVector3(0.5, 0.005, 0.5), 0.0, btVector3(0, 0, 0));
    RodSettings rod = limpRope();
    rod.gravity = Vec3::Zero();
    rod.restLength = 0.6;
    RopeObject rope(Rod::fromSegment(rod, Vec3(-0.3, 0.3, 0.0), Vec3(0.3, 0.3, 0.0)));
    rope.rod().setVelocities(PointList(static_cast<std::size_t>(rope.rod().controlPointCount()), Vec3(0, -speed, 0)));
    physics.ropes().addRope(rope);
    double lowest = 1.0;
    for (int i = 0; i < 240; ++i) {
      stepWorld(physics.world(), 1);
      ASSERT_TRUE(rope.lastStep().ok);
      lowest = std::min(lowest, lowestPoint(rope.rod()));
    }
    // The centre line never crossed the plate's top face: measured 8.9-10.0 mm above it at every speed
    // (the README's figure; at most 1.1 mm of the 10 mm radius inside), bound 2 mm inside.
    EXPECT_GT(lowest, 0.005 + 0.8 * rod.radius) << speed << " m/s";
    EXPECT_GT(rope.rod().momentum().y(), -1e-6) << speed << " m/s";  // stopped or bounced
    std::printf("fast plate at %.0f m/s: lowest centre-line point %.4f m (plate top 0.005 m)\n", speed, lowest);
  }
}

// No gravity, no ground: a rope hits a free box; the impulses on the box are exactly the opposite of
// the forces the rope felt, so total linear momentum is conserved to round-off. With adaptivity on (the
// default) a knot removal may also change the rope's velocity field by up to
// removalVelocityErrorBound, so its momentum by at most the rope's mass times that per removal; the
// drift is bounded by that sum, and by round-off where no removal happened.
TEST(RopeWorldScenario, RopeAndBoxCollidingConserveLinearMomentum) {
  for (const bool adaptive : {false, true}) {
    demos::PhysicsWorld physics(btVector3(0, 0, 0));
    btRigidBody* box = physics.addBox(btVector3(0.1, 0.1, 0.1), 2.0, btVector3(0.05, 0, 0));
    box->setActivationState(DISABLE_DEACTIVATION);  // sleeping zeroes velocities
    box->setLinearVelocity(btVector3(0, 0.5, 0));
    RodSettings rod = limpRope();
    rod.gravity = Vec3::Zero();
    rod.massDamping = 0.0;  // absolute-velocity damping would take momentum out
    rod.adaptive = adaptive;
    rod.restLength = 0.8;
    RopeObject rope(Rod::fromSegment(rod, Vec3(-0.4, 0.4, 0.0), Vec3(0.4, 0.4, 0.0)));
    rope.rod().setVelocities(PointList(static_cast<std::size_t>(rope.rod().controlPointCount()), Vec3(0, -3, 0)));
    physics.ropes().addRope(rope);
    auto total = [&]() -> Vec3 {
      const btVector3 p = box->getLinearVelocity() / box->getInvMass();
      return rope.rod().momentum() + Vec3(p.x(), p.y(), p.z());
    };
    const Vec3 initial = total();
    double worst = 0.0, removalBound = 0.0;
    int contactSteps = 0, insertions = 0, removals = 0;
    for (int i = 0; i < 360; ++i) {
      stepWorld(physics.world(), 1);
      ASSERT_TRUE(rope.lastStep().ok);
      contactSteps += rope.lastStep().contacts > 0 ? 1 : 0;
      insertions += rope.lastStep().insertions;
      removals += rope.lastStep().removals;
      removalBound += rope.lastStep().removals * rope.rod().mass() * rod.removalVelocityErrorBound;
      worst = std::max(worst, (total() - initial).norm() / initial.norm());
    }
    EXPECT_GT(contactSteps, 5);
    EXPECT_LT(box->getLinearVelocity().y(), 0.25);  // slowed from 0.5 m/s by the rope that hit it
    // Measured (double build): 1.6e-12 relative with adaptivity off. Float Bullet rounds the box's
    // velocity to ~1e-7 per impulse.
    const double roundOff = sizeof(btScalar) == sizeof(double) ? 1e-11 : 1e-5;
    EXPECT_LT(worst, roundOff + removalBound / initial.norm()) << "adaptive " << adaptive;
    if (adaptive) {
      EXPECT_GT(insertions, 0);  // the impact bent the rope: adaptivity had work to do
    }
    std::printf("momentum (adaptive %d): worst relative drift %.3g over %d contact steps, %d insertions, %d removals "
                "(removal bound %.3g)\n", adaptive, worst, contactSteps, insertions, removals, removalBound / initial.norm());
  }
}

// The same collision with nothing damped (rope, contact, speculative contact and friction off), default
// adaptivity: knots are inserted at the contacts and removed after, and the total energy of rope and
// box must never exceed its start by more than what removals may change (kinetic energy by
// m (v dv + dv^2 / 2) each) at any step out of contact.
// It failed on earlier contact code (an insertion at a contact sampled a deformation the locking-free
// rule holds no energy for, docs/method.md §7: 2.4 J from 0.145 J); it holds on this code, measured
// on 2026-12-02: 0.1445 J -> 0.0236 J at 1 m/s (234 contact steps, 24 insertions, 28 removals) and
// 1.3006 J -> 0.2190 J at 3 m/s (104, 55, 50).
TEST(RopeWorldScenario, RopeAndBoxCollidingWithoutDampingNeverGainEnergy) {
  for (const double speed : {1.0, 3.0}) {
    demos::PhysicsWorld physics(btVector3(0, 0, 0));
    btRigidBody* box = physics.addBox(btVector3(0.1, 0.1, 0.1), 2.0, btVector3(0.05, 0, 0));
    box->setActivationState(DISABLE_DEACTIVATION);
    box->setFriction(0.0);
    RodSettings rod = limpRope();
    rod.gravity = Vec3::Zero();
    rod.massDamping = rod.stiffnessDamping = rod.materialDamping = 0.0;
    ASSERT_TRUE(rod.adaptive);  // the default
    rod.restLength = 0.8;
    BulletRopeSettings settings;
    settings.lineContactDamping = settings.contactDamping = settings.friction = 0.0;
    settings.lineSpeculativeDamping = settings.speculativeDamping = 0.0;
    RopeObject rope(Rod::fromSegment(rod, Vec3(-0.4, 0.4, 0.0), Vec3(0.4, 0.4, 0.0)), settings);
    rope.rod().setVelocities(PointList(static_cast<std::size_t>(rope.rod().controlPointCount()), Vec3(0, -speed, 0)));
    physics.ropes().addRope(rope);
    auto total = [&] {
      const btVector3 v = box->getLinearVelocity(), w = box->getAngularVelocity();
      return rope.rod().totalEnergy() + 0.5 * v.length2() / box->getInvMass() +
             0.5 * w.dot(box->getInvInertiaTensorWorld().inverse() * w);
    };
    const double initial = total();
    double allowance = 0.0, highest = -initial;
    int insertions = 0, removals = 0, contactSteps = 0;
    for (int i = 0; i < 480; ++i) {
      double fastest = 0.0;  // the field's speed is at most its fastest control point's (convex hull)
      for (const Vec3& v : rope.rod().velocities()) fastest = std::max(fastest, v.norm());
      stepWorld(physics.world(), 1);
      ASSERT_TRUE(rope.lastStep().ok);
      const RopeStepRecord& step = rope.lastStep();
      insertions += step.insertions;
      removals += step.removals;
      const double dv = rod.removalVelocityErrorBound;
      allowance += step.removals * rope.rod().mass() * (fastest * dv + 0.5 * dv * dv);
      if (step.contacts > 0) {
        ++contactSteps;
        continue;  // the contact's own potential is not counted
      }
      highest = std::max(highest, total() - initial - allowance);
    }
    EXPECT_GT(contactSteps, 5);
    EXPECT_GT(insertions, 0);
    EXPECT_GT(removals, 0);
    EXPECT_LE(highest, 1e-12 * initial) << speed << " m/s";
    EXPECT_LT(total(), initial);
    std::printf("undamped rope on a free box at %.0f m/s: energy %.4f -> %.4f J, %d contact steps, %d insertions, %d "
                "removals\n", speed, initial, total(), contactSteps, insertions, removals);
  }
}

// A box sliding into a rope stretched between two pins is stopped by it (and thrown back).
TEST(RopeWorldScenario, BoxSlidingIntoPinnedRopeIsStopped) {
  demos::PhysicsWorld physics(btVector3(0, 0, 0));
  btRigidBody* box = physics.addBox(btVector3(0.05, 0.05, 0.05), 1.0, btVector3(0, 0, -0.3));
  box->setLinearVelocity(btVector3(0, 0, 3));
  RodSettings rod = limpRope(0.005);
  rod.gravity = Vec3::Zero();
  rod.restLength = 1.0;
  RopeObject rope(Rod::fromSegment(rod, Vec3(-0.5, 0, 0), Vec3(0.5, 0, 0)));
  physics.ropes().addRope(rope);
  rope.attachToPoint(rope.rod().beginParameter(), btVector3(-0.5, 0, 0));
  rope.attachToPoint(rope.rod().endParameter(), btVector3(0.5, 0, 0));
  double furthest = -1.0;
  for (int i = 0; i < 480; ++i) {
    stepWorld(physics.world(), 1);
    ASSERT_TRUE(rope.lastStep().ok);
    furthest = std::max(furthest, static_cast<double>(box->getCenterOfMassPosition().z()));
  }
  EXPECT_LT(furthest, 0.3);  // stopped well before passing the rope
  EXPECT_LT(box->getLinearVelocity().z(), 0.0);  // and thrown back
  EXPECT_LT(box->getCenterOfMassPosition().z(), 0.0);
  std::printf("two-way: box front reached z = %.3f m, final v_z = %.3f m/s\n", furthest + 0.05,
              static_cast<double>(box->getLinearVelocity().z()));
}

// A box fast enough to cross more than Bullet's broadphase slack (gContactBreakingThreshold, 2 cm) in a
// substep: Bullet's pair for it and the rope would only appear once it is already past the rope's
// surface (RopeWorld::addFastBodies). The rope must see it in the substep before it arrives, as a
// speculative contact, and meet it there.
TEST(RopeWorldScenario, FastBoxIsCaughtBeforeItReachesTheRope) {
  for (const double speed : {20.0, 30.0, 50.0}) {
    demos::PhysicsWorld physics(btVector3(0, 0, 0));
    // Front face 1.6 substeps of travel from the rope's surface: 0.6 substeps (5 to 12.5 cm) after
    // Bullet's first integration, more than the 2 cm slack plus the rope's 1 cm margin.
    const double radius = 0.005, gap = 1.6 * speed * kStep;
    btRigidBody* box = physics.addBox(btVector3(0.05, 0.05, 0.05), 1.0, btVector3(0, 0, btScalar(-radius - gap - 0.05)));
    box->setLinearVelocity(btVector3(0, 0, btScalar(speed)));
    RodSettings rod = limpRope(radius);
    rod.gravity = Vec3::Zero();
    RopeObject rope(Rod::fromSegment(rod, Vec3(-0.5, 0, 0), Vec3(0.5, 0, 0)));
    physics.ropes().addRope(rope);
    rope.attachToPoint(rope.rod().beginParameter(), btVector3(-0.5, 0, 0));
    rope.attachToPoint(rope.rod().endParameter(), btVector3(0.5, 0, 0));
    stepWorld(physics.world(), 1);
    // Closing within the substep: a speculative contact, not yet touching.
    ASSERT_TRUE(rope.lastStep().ok);
    const int caught = rope.lastStep().contacts;
    EXPECT_GT(caught, 0) << speed << " m/s";
    EXPECT_EQ(rope.lastStep().maxPenetration, 0.0) << speed << " m/s";
    double deepest = 0.0;
    for (int i = 1; i < 4; ++i) {
      stepWorld(physics.world(), 1);
      deepest = std::max(deepest, rope.lastStep().maxPenetration);
    }
    std::printf("fast box at %.0f m/s: %d contacts in the first substep, deepest contact %.4f m in the next three\n",
                speed, caught, deepest);
  }
}

// The user steps with 1/60 s frames and 4 substeps: the rope steps once per substep (240 Hz) and
// rests on the box as with single steps.
TEST(RopeWorldScenario, WorksUnchangedWithSubsteps) {
  demos::DrapeScene scene{demos::DrapeSceneSettings{}};
  long substeps = 0;
  scene.physics().ropes().setSubstepCallback([&](const ContactReport& report) {
    ++substeps;
    EXPECT_DOUBLE_EQ(report.timeStep, btScalar(1.0 / 240.0));
  });
  for (int frame = 0; frame < 4 * 60; ++frame) {
    scene.physics().world().stepSimulation(btScalar(1.0 / 60.0), 4, btScalar(1.0 / 240.0));
  }
  EXPECT_EQ(substeps, 4 * 4 * 60);
  const double radius = scene.rope().rod().settings().radius;
  EXPECT_NEAR(scene.lowestPoint(), 0.2 + radius, 0.1 * radius);
  EXPECT_LT(scene.rope().lastStep().maxPenetration, 0.1 * radius);
}

// Two identical worlds give bitwise identical ropes and bodies (candidate bodies are processed in
// world order, not by pointer).
TEST(RopeWorldScenario, TwinRunsAreBitwiseIdentical) {
  demos::DrapeScene first{demos::DrapeSceneSettings::thinBar()};
  demos::DrapeScene second{demos::DrapeSceneSettings::thinBar()};
  for (int i = 0; i < 480; ++i) {
    first.step();
    second.step();
  }
  EXPECT_EQ(first.rope().rod().knots().size(), second.rope().rod().knots().size());
  EXPECT_EQ(first.rope().rod().controlPoints(), second.rope().rod().controlPoints());
  EXPECT_EQ(first.rope().rod().velocities(), second.rope().rod().velocities());
  EXPECT_EQ(first.rope().contacts().size(), second.rope().contacts().size());
}

// Side detection (RopeWorld::ContactDetectionThread::kSide) does the same work in another order: a
// world with it and one without (kCaller) give the same ropes and contacts, bit for bit, and the one
// with it did use the side thread. The 2 m pile (one rope, self-contact) and a rope held round a taut rope
// (two ropes, distributed rope-rope contact with stick state).
template <class Scene>
void expectSideDetectionChangesNoBit(Scene& inTurn, Scene& beside, int steps) {
  inTurn.physics().ropes().setContactDetectionThread(RopeWorld::ContactDetectionThread::kCaller);
  beside.physics().ropes().setContactDetectionThread(RopeWorld::ContactDetectionThread::kSide);
  int besideSubsteps = 0, pairedSubsteps = 0;
  inTurn.physics().ropes().setSubstepCallback([&](const ContactReport& report) {
    EXPECT_FALSE(report.detectedOnSideThread);
    if (!report.ropeContacts.empty()) ++pairedSubsteps;
  });
  beside.physics().ropes().setSubstepCallback([&](const ContactReport& report) {
    if (report.detectedOnSideThread) ++besideSubsteps;
  });
  for (int i = 0; i < steps; ++i) {
    inTurn.step();
    beside.step();
  }
  const auto& a = inTurn.physics().ropes().ropes();
  const auto& b = beside.physics().ropes().ropes();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t r = 0; r < a.size(); ++r) {
    EXPECT_EQ(a[r]->rod().knots().values(), b[r]->rod().knots().values()) << "rope " << r;
    EXPECT_EQ(a[r]->rod().controlPoints(), b[r]->rod().controlPoints()) << "rope " << r;
    EXPECT_EQ(a[r]->rod().velocities(), b[r]->rod().velocities()) << "rope " << r;
    EXPECT_EQ(a[r]->lastStep().ropeContacts, b[r]->lastStep().ropeContacts) << "rope " << r;
    EXPECT_EQ(a[r]->warnings().exceptions, 0) << "rope " << r;
  }
  const ContactReport& x = inTurn.physics().ropes().lastReport();
  const ContactReport& y = beside.physics().ropes().lastReport();
  ASSERT_EQ(x.ropeContacts.size(), y.ropeContacts.size());
  for (std::size_t k = 0; k < x.ropeContacts.size(); ++k) {
    EXPECT_EQ(x.ropeContacts[k].sA, y.ropeContacts[k].sA);
    EXPECT_EQ(x.ropeContacts[k].sB, y.ropeContacts[k].sB);
    EXPECT_EQ(x.ropeContacts[k].force, y.ropeContacts[k].force);
    EXPECT_EQ(x.ropeContacts[k].active, y.ropeContacts[k].active);
  }
  // Most substeps had rope contacts, and most of those went to the side thread (the first ones with
  // pairs do not: a substep uses it when the last one had pairs enough).
  EXPECT_GT(pairedSubsteps, steps / 2);
  EXPECT_GT(besideSubsteps, pairedSubsteps / 2);
}

TEST(RopeWorldScenario, SideDetectionChangesNoBitInThePile) {
  demos::PileScene inTurn{demos::PileSceneSettings{}};
  demos::PileScene beside{demos::PileSceneSettings{}};
  expectSideDetectionChangesNoBit(inTurn, beside, 360);  // 1.5 s: falls, lands, heaps
}

TEST(RopeWorldScenario, SideDetectionChangesNoBitRoundATautRope) {
  demos::CapstanSceneSettings settings;
  settings.obstacle = demos::CapstanSceneSettings::Obstacle::kTautRope;
  settings.loadRatio = 0.9 * settings.capstanLimit();
  demos::CapstanScene inTurn{settings};
  demos::CapstanScene beside{settings};
  expectSideDetectionChangesNoBit(inTurn, beside, 240);
}

TEST(RopeWorld, ContactDetectionThreadIsTheFasterWhereTheMachineHasTwoThreads) {
  using Where = RopeWorld::ContactDetectionThread;
  demos::PhysicsWorld physics;
  EXPECT_EQ(physics.ropes().contactDetectionThread(),
            std::thread::hardware_concurrency() > 1 ? Where::kFaster : Where::kCaller);
  physics.ropes().setContactDetectionThread(Where::kSide);
  EXPECT_EQ(physics.ropes().contactDetectionThread(), Where::kSide);
  try {
    physics.ropes().setContactDetectionThread(static_cast<Where>(7));
    ADD_FAILURE() << "no exception";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("where"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find('7'), std::string::npos) << error.what();
  }
  EXPECT_EQ(physics.ropes().contactDetectionThread(), Where::kSide);  // unchanged
}

// The default (kFaster) times both ways and keeps to whichever is faster, with the same results:
// the pile under it is the pile in turn, bit for bit.
TEST(RopeWorldScenario, TimedChoiceOfTheDetectionThreadChangesNoBit) {
  demos::PileScene inTurn{demos::PileSceneSettings{}};
  demos::PileScene timed{demos::PileSceneSettings{}};
  inTurn.physics().ropes().setContactDetectionThread(RopeWorld::ContactDetectionThread::kCaller);
  timed.physics().ropes().setContactDetectionThread(RopeWorld::ContactDetectionThread::kFaster);
  int beside = 0;
  timed.physics().ropes().setSubstepCallback([&](const ContactReport& report) {
    if (report.detectedOnSideThread) ++beside;
  });
  for (int i = 0; i < 300; ++i) {
    inTurn.step();
    timed.step();
  }
  EXPECT_GE(beside, 8);  // at least the first trial's side substeps
  EXPECT_EQ(inTurn.rope().rod().controlPoints(), timed.rope().rod().controlPoints());
  EXPECT_EQ(inTurn.rope().rod().velocities(), timed.rope().rod().velocities());
}

TEST(RopeWorld, AddAndRemoveAreSymmetric) {
  demos::PhysicsWorld physics;
  const int before = physics.world().getNumCollisionObjects();
  RopeObject rope(Rod::fromSegment(limpRope(), Vec3(0, 1, 0), Vec3(1, 1, 0)));
  physics.ropes().addRope(rope);
  EXPECT_TRUE(physics.ropes().contains(rope));
  EXPECT_EQ(physics.world().getNumCollisionObjects(), before + 1);  // one object per rope
  stepWorld(physics.world(), 10);
  physics.ropes().removeRope(rope);
  EXPECT_FALSE(physics.ropes().contains(rope));
  EXPECT_EQ(rope.world(), nullptr);
  EXPECT_EQ(physics.world().getNumCollisionObjects(), before);
  physics.ropes().addRope(rope);  // and back again
  stepWorld(physics.world(), 10);
  EXPECT_EQ(physics.world().getNumCollisionObjects(), before + 1);  // one object per rope
}

TEST(RopeWorld, BadInputThrowsAndChangesNothing) {
  demos::PhysicsWorld physics;
  RopeObject rope(Rod::fromSegment(limpRope(), Vec3(0, 1, 0), Vec3(1, 1, 0)));
  RopeObject stranger(Rod::fromSegment(limpRope(), Vec3(0, 2, 0), Vec3(1, 2, 0)));
  physics.ropes().addRope(rope);
  const int objects = physics.world().getNumCollisionObjects();
  const PointList points = rope.rod().controlPoints();

  EXPECT_THROW(physics.ropes().addRope(rope), InvalidArgument);       // twice
  EXPECT_THROW(physics.ropes().removeRope(stranger), InvalidArgument); // never added
  demos::PhysicsWorld other;
  EXPECT_THROW(other.ropes().addRope(rope), InvalidArgument);          // in another world

  // A body that is not in the world.
  btBoxShape shape(btVector3(0.1, 0.1, 0.1));
  btRigidBody outsider(1.0, nullptr, &shape);
  EXPECT_THROW(rope.attachToBody(0.5, outsider, btVector3(0, 0, 0)), InvalidArgument);
  btRigidBody* inside = physics.addBox(btVector3(0.1, 0.1, 0.1), 1.0, btVector3(3, 3, 3));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(rope.attachToBody(nan, *inside, btVector3(0, 0, 0)), InvalidArgument);
  EXPECT_THROW(rope.attachToBody(5.0, *inside, btVector3(0, 0, 0)), InvalidArgument);
  EXPECT_THROW(rope.attachToBody(0.5, *inside, btVector3(0, btScalar(nan), 0)), InvalidArgument);
  AttachmentSettings badAttachment;
  badAttachment.stiffness = -1.0;
  EXPECT_THROW(rope.attachToBody(0.5, *inside, btVector3(0, 0, 0), badAttachment), InvalidArgument);
  EXPECT_THROW(rope.attachToPoint(0.5, btVector3(btScalar(nan), 0, 0)), InvalidArgument);
  EXPECT_THROW(rope.setAttachmentTarget(99, btVector3(0, 0, 0)), InvalidArgument);
  EXPECT_THROW(rope.removeAttachment(99), InvalidArgument);
  const int pin = rope.attachToPoint(0.0, btVector3(0, 1, 0));
  EXPECT_THROW(rope.setAttachmentTarget(pin, btVector3(0, btScalar(nan), 0)), InvalidArgument);
  EXPECT_THROW(stranger.attachToBody(0.5, *inside, btVector3(0, 0, 0)), InvalidArgument);  // rope in no world
  BulletRopeSettings bad;
  bad.lineContactStiffness = nan;
  EXPECT_THROW(RopeObject(Rod::fromSegment(limpRope(), Vec3(0, 1, 0), Vec3(1, 1, 0)), bad), InvalidArgument);
  bad = BulletRopeSettings();
  bad.speculativeDamping = -1.0;
  EXPECT_THROW(RopeObject(Rod::fromSegment(limpRope(), Vec3(0, 1, 0), Vec3(1, 1, 0)), bad), InvalidArgument);
  bad = BulletRopeSettings();
  bad.capsulesPerSpan = 0;
  EXPECT_THROW(RopeObject(Rod::fromSegment(limpRope(), Vec3(0, 1, 0), Vec3(1, 1, 0)), bad), InvalidArgument);
  // The line-contact settings: each out-of-range value is refused naming its field.
  const auto refusedNaming = [&](const char* field, const std::function<void(BulletRopeSettings&)>& spoil) {
    BulletRopeSettings settings;
    spoil(settings);
    try {
      RopeObject(Rod::fromSegment(limpRope(), Vec3(0, 1, 0), Vec3(1, 1, 0)), settings);
    } catch (const InvalidArgument& error) {
      EXPECT_NE(std::string(error.what()).find(field), std::string::npos) << error.what();
      return;
    }
    ADD_FAILURE() << field << " was accepted";
  };
  refusedNaming("settings.lineContactStiffness", [](BulletRopeSettings& b) { b.lineContactStiffness = 0.0; });
  refusedNaming("settings.lineContactDamping", [](BulletRopeSettings& b) { b.lineContactDamping = -1.0; });
  refusedNaming("settings.lineSpeculativeDamping", [&](BulletRopeSettings& b) { b.lineSpeculativeDamping = nan; });
  refusedNaming("settings.contactQuadraturePoints", [](BulletRopeSettings& b) { b.contactQuadraturePoints = 0; });
  refusedNaming("settings.contactQuadraturePoints", [](BulletRopeSettings& b) { b.contactQuadraturePoints = 9; });
  refusedNaming("settings.concentratedContactRatio", [](BulletRopeSettings& b) { b.concentratedContactRatio = 0.0; });
  refusedNaming("settings.concentratedContactRatio", [](BulletRopeSettings& b) { b.concentratedContactRatio = 1.5; });
  refusedNaming("settings.concentratedContactRatio", [&](BulletRopeSettings& b) { b.concentratedContactRatio = nan; });

  EXPECT_EQ(rope.attachments().size(), 1u);
  EXPECT_EQ(physics.world().getNumCollisionObjects(), objects + 1);  // + the box added above
  EXPECT_EQ(rope.rod().controlPoints(), points);
  EXPECT_TRUE(physics.ropes().contains(rope));
  EXPECT_EQ(stranger.world(), nullptr);
}

// A body whose transform became NaN is skipped (and reported); the rope stays finite.
TEST(RopeWorld, NonFiniteBodyIsSkippedAndReported) {
  demos::PhysicsWorld physics(btVector3(0, 0, 0));
  btRigidBody* box = physics.addBox(btVector3(0.1, 0.1, 0.1), 0.0, btVector3(0.5, 0.8995, 0));  // 0.5 mm into the rope
  RopeObject rope(Rod::fromSegment(limpRope(), Vec3(0, 1, 0), Vec3(1, 1, 0)));
  physics.ropes().addRope(rope);
  stepWorld(physics.world(), 2);
  ASSERT_FALSE(rope.contacts().empty());  // the box is found
  btTransform broken = box->getWorldTransform();
  broken.setOrigin(btVector3(std::numeric_limits<btScalar>::quiet_NaN(), 1, 0));
  box->setWorldTransform(broken);
  rope.substep({box}, kStep);  // as the action would, with the broken body as a candidate
  EXPECT_TRUE(rope.lastStep().ok);
  EXPECT_EQ(rope.lastStep().skippedBodies, 1);
  EXPECT_TRUE(rope.contacts().empty());
  for (const Vec3& p : rope.rod().controlPoints()) EXPECT_TRUE(p.allFinite());
  box->setWorldTransform(btTransform::getIdentity());
}

// Works in a btSoftRigidDynamicsWorld next to a soft body (Bullet's own soft-rigid handling does not
// see the rope's capsules as obstacles).
TEST(RopeWorldScenario, WorksInSoftRigidWorld) {
  btSoftBodyRigidBodyCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher(&configuration);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btSoftRigidDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
  world.setGravity(btVector3(0, -9.81, 0));
  btStaticPlaneShape groundShape(btVector3(0, 1, 0), 0);
  btRigidBody ground(0, nullptr, &groundShape);
  world.addRigidBody(&ground);
  {
    RopeWorld ropes(world);
    RopeObject rope(Rod::fromSegment(limpRope(), Vec3(-0.5, 0.3, 0), Vec3(0.5, 0.3, 0)));
    ropes.addRope(rope);
    for (int i = 0; i < 480; ++i) world.stepSimulation(btScalar(kStep), 1, btScalar(kStep));
    EXPECT_TRUE(rope.lastStep().ok);
    EXPECT_NEAR(lowestPoint(rope.rod()), 0.01, 0.001);
  }
  world.removeRigidBody(&ground);
}

// Gravity comes from the world by default, every substep, scaled by gravityScale; kRod keeps the
// rod's own. A free rope's centre of mass falls at exactly the world's gravity (backward Euler is
// exact for a uniform field), and follows a change of the world's gravity at once.
TEST(RopeWorldScenario, RopesFollowTheWorldsGravityUnlessTheyKeepTheirOwn) {
  demos::PhysicsWorld physics(btVector3(0, 0, -9.81));  // z up, unlike RodSettings' default
  RodSettings rod;  // gravity (0, -9.81, 0), the default (material) damping
  RopeObject follows(Rod::fromSegment(rod, Vec3(0, 0, 1), Vec3(1, 0, 1)));
  BulletRopeSettings halved;
  halved.gravityScale = 0.5;
  RopeObject scaled(Rod::fromSegment(rod, Vec3(0, 2, 1), Vec3(1, 2, 1)), halved);
  BulletRopeSettings own;
  own.gravitySource = BulletRopeSettings::GravitySource::kRod;
  RodSettings weightless = rod;
  weightless.gravity = Vec3::Zero();
  RopeObject keeps(Rod::fromSegment(weightless, Vec3(0, 4, 1), Vec3(1, 4, 1)), own);
  for (RopeObject* rope : {&follows, &scaled, &keeps}) physics.ropes().addRope(*rope);
  stepWorld(physics.world(), 120);  // 0.5 s
  const auto velocity = [](const RopeObject& rope) -> Vec3 { return rope.rod().momentum() / rope.rod().mass(); };
  EXPECT_LT((velocity(follows) - Vec3(0, 0, -9.81 * 0.5)).norm(), 1e-9 * 9.81);
  EXPECT_LT((velocity(scaled) - Vec3(0, 0, -0.5 * 9.81 * 0.5)).norm(), 1e-9 * 9.81);
  EXPECT_LT(velocity(keeps).norm(), 1e-12);  // weightless: only round-off of its unstretched state
  EXPECT_EQ(follows.rod().settings().gravity, Vec3(0, 0, -9.81));
  // The world's gravity changes: the ropes that follow it feel the new one from the next substep.
  physics.world().setGravity(btVector3(0, 0, 0));
  const Vec3 before = velocity(follows);
  stepWorld(physics.world(), 60);
  EXPECT_LT((velocity(follows) - before).norm(), 1e-12);
}

TEST(RopeWorld, GravitySettingsRejectBadInputNamingTheField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  BulletRopeSettings bad;
  bad.gravityScale = nan;
  try {
    RopeObject rope(Rod::fromSegment(RodSettings(), Vec3(0, 1, 0), Vec3(1, 1, 0)), bad);
    ADD_FAILURE() << "gravityScale = NaN was accepted";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("settings.gravityScale"), std::string::npos) << error.what();
  }
  Rod rod = Rod::fromSegment(RodSettings(), Vec3(0, 1, 0), Vec3(1, 1, 0));
  EXPECT_THROW(rod.setGravity(Vec3(0, nan, 0)), InvalidArgument);
  EXPECT_EQ(rod.settings().gravity, RodSettings().gravity);  // unchanged
}

// Loads on a rope in a world act in the next substep, whether given to the RopeObject or queued on
// its rod: an impulse J changes the momentum by exactly J, a force F by F h, and neither acts again.
TEST(RopeWorldScenario, ForcesAndImpulsesActInTheNextSubstepOnly) {
  demos::PhysicsWorld physics(btVector3(0, 0, 0));
  // Knot removal changes a moving rope's momentum by up to mass * removalVelocityErrorBound (measured
  // here: 3e-6 N s); this test checks the loads, so the knot vector stays fixed.
  RodSettings fixedKnots;
  fixedKnots.adaptive = false;
  RopeObject rope(Rod::fromSegment(fixedKnots, Vec3(0, 1, 0), Vec3(1, 1, 0)));
  physics.ropes().addRope(rope);
  const Vec3 impulse(0.01, -0.02, 0.005);
  rope.applyImpulse(0.3, btVector3(0.01, -0.02, 0.005));
  stepWorld(physics.world(), 1);
  EXPECT_LT((rope.rod().momentum() - impulse).norm(), 1e-12 * impulse.norm());
  stepWorld(physics.world(), 1);  // acted once
  EXPECT_LT((rope.rod().momentum() - impulse).norm(), 1e-12 * impulse.norm());
  const Vec3 force(0.5, 0.0, -0.25);
  rope.applyForce(0.7, btVector3(0.5, 0.0, -0.25));
  rope.rod().addForce(0.1, force);  // queued on the rod: not dropped either
  stepWorld(physics.world(), 1);
  const Vec3 expected = impulse + 2.0 * kStep * force;
  EXPECT_LT((rope.rod().momentum() - expected).norm(), 1e-12 * expected.norm());

  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const auto& bad : {std::function<void()>([&] { rope.applyForce(nan, btVector3(1, 0, 0)); }),
                          std::function<void()>([&] { rope.applyForce(0.5, btVector3(btScalar(nan), 0, 0)); }),
                          std::function<void()>([&] { rope.applyImpulse(2.0, btVector3(1, 0, 0)); })}) {
    EXPECT_THROW(bad(), InvalidArgument);
  }
  stepWorld(physics.world(), 1);  // nothing was queued by the refused calls
  EXPECT_LT((rope.rod().momentum() - expected).norm(), 1e-12 * expected.norm());
}

// RopeWorld lends one contact-sample buffer to each rope for its visit (BodyContacts::swapScratch):
// a rope finished within its visit gives it back, one that waits keeps it. Ropes that wait: A and B,
// each lying on a dynamic box it pushes (A without self-contact: it waits only for its end of
// substep; B with it: for the rope-rope solve too). Rope C, resting on the ground and visited after
// them, is finished at once and must not write into their samples: the contact forces each rope
// reports at its end of substep carry its weight, and every rope and box steps exactly as it does
// with that rope alone in its world.
TEST(RopeWorldScenario, RopesFinishedInTheirVisitAndRopesThatWaitStepAsIfAlone) {
  enum Ropes { kA = 1, kB = 2, kC = 4 };
  struct World {
    static BulletRopeSettings noSelfContact() {
      BulletRopeSettings settings;
      settings.selfContact = false;
      return settings;
    }
    demos::PhysicsWorld physics;
    RopeObject a{Rod::fromSegment(limpRope(), Vec3(-0.4, 0.41, 0), Vec3(0.4, 0.41, 0)), noSelfContact()};
    RopeObject b{Rod::fromSegment(limpRope(), Vec3(-0.4, 0.41, 1.0), Vec3(0.4, 0.41, 1.0))};
    RopeObject c{Rod::fromSegment(limpRope(), Vec3(-0.4, 0.01, 2.0), Vec3(0.4, 0.01, 2.0))};
    btRigidBody* boxA = nullptr;
    btRigidBody* boxB = nullptr;
    explicit World(int ropes) {
      physics.addGround();
      boxA = physics.addBox(btVector3(0.5, 0.2, 0.2), 5.0, btVector3(0, 0.2, 0));
      boxB = physics.addBox(btVector3(0.5, 0.2, 0.2), 5.0, btVector3(0, 0.2, 1.0));
      for (btRigidBody* box : {boxA, boxB}) box->setActivationState(DISABLE_DEACTIVATION);
      if (ropes & kA) physics.ropes().addRope(a);
      if (ropes & kB) physics.ropes().addRope(b);
      if (ropes & kC) physics.ropes().addRope(c);
    }
  };
  World all(kA | kB | kC), aAlone(kA), bAlone(kB), cAlone(kC);
  for (int i = 0; i < 120; ++i) {
    for (World* world : {&all, &aAlone, &bAlone, &cAlone}) stepWorld(world->physics.world(), 1);
    if (i < 10) continue;  // all three have landed by then
    ASSERT_GT(all.a.lastStep().contacts, 0) << "step " << i;
    ASSERT_GT(all.b.lastStep().contacts, 0) << "step " << i;
    ASSERT_GT(all.c.lastStep().contacts, 0) << "step " << i;
  }
  EXPECT_EQ(all.a.rod().controlPoints(), aAlone.a.rod().controlPoints());
  EXPECT_EQ(all.a.rod().velocities(), aAlone.a.rod().velocities());
  EXPECT_EQ(all.b.rod().controlPoints(), bAlone.b.rod().controlPoints());
  EXPECT_EQ(all.b.rod().velocities(), bAlone.b.rod().velocities());
  EXPECT_EQ(all.c.rod().controlPoints(), cAlone.c.rod().controlPoints());
  EXPECT_EQ(all.c.rod().velocities(), cAlone.c.rod().velocities());
  // The contact forces each rope reports (and gives its box) come from its samples at its end of
  // substep.
  const auto sameContacts = [](const RopeObject& x, const RopeObject& y) {
    if (x.contacts().size() != y.contacts().size()) return false;
    for (std::size_t k = 0; k < x.contacts().size(); ++k) {
      const RopeContactRecord& p = x.contacts()[k];
      const RopeContactRecord& q = y.contacts()[k];
      if (p.s != q.s || p.force != q.force || p.active != q.active || p.sticking != q.sticking) return false;
    }
    return true;
  };
  // A rope at rest on its support: its contacts carry its weight (a rope that waits lost them if its
  // samples were not its own at its end of substep).
  for (const RopeObject* rope : {&all.a, &all.b, &all.c}) {
    double lift = 0.0;  // N
    for (const RopeContactRecord& record : rope->contacts()) lift += record.active ? record.force.y() : 0.0;
    EXPECT_NEAR(lift, rope->rod().mass() * 9.81, 0.02 * rope->rod().mass() * 9.81);
  }
  EXPECT_TRUE(sameContacts(all.a, aAlone.a));
  EXPECT_TRUE(sameContacts(all.b, bAlone.b));
  EXPECT_TRUE(sameContacts(all.c, cAlone.c));
  EXPECT_EQ(all.boxA->getWorldTransform().getOrigin(), aAlone.boxA->getWorldTransform().getOrigin());
  EXPECT_EQ(all.boxB->getWorldTransform().getOrigin(), bAlone.boxB->getWorldTransform().getOrigin());
}

}  // namespace
}  // namespace rope::bullet
