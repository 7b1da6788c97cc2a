// SPDX-License-Identifier: MIT
// Extremes never explode (issue 17). Stress scenes with default settings (RodSettings{},
// BulletRopeSettings{}, Bullet's stock world; only what the scene is about is changed), each asserting
//   - no NaN (floating-point traps on, and every rope's state checked finite after every step),
//   - no exception escapes stepSimulation,
//   - no point of a rope faster than 2 (v_driver + g T): the fastest driver's speed plus free fall
//     over the run of T seconds, times 2 (control-point speeds, which bound the curve's: a B-spline's
//     velocity is a convex combination of them),
//   - no rope put to rest for failing kFailuresBeforeRest substeps in a row (frozen ropes cannot
//     explode, which would make the other checks empty),
//   - where nothing drives the scene (only gravity, static pins and the initial state), a total
//     energy (ropes and bodies, kinetic, elastic and gravitational from the ground plane y = 0) that
//     never exceeds its start by more than 1 %:
// a rope squeezed between two boxes driven together; a rope under a 1000 kg box; E = 1e13 Pa with a
// 0.5 mm radius at 1/60 s; a rope hit by a 50 m/s box; a rope wound ten times round a spinning
// cylinder; and, on the rod alone, a thousand random knot insertions and removals during a swing.
// The figures of each run are printed (speed, energy growth, failed substeps, deepest contact).
//
// Measured on the default settings (2026-12-02):
//   - RopeHitByAFiftyMetrePerSecondBox: no energy growth, rope up to 13.7 m/s (bound 110). The box
//     drags the rope's middle 0.2 m sideways in one substep, and the step linearised once about the
//     start moves the rope along its old tangents: that trial holds 1,652 J of stretching, most of it
//     beyond the step's quadratic model, and kept it made the scene's energy +61 % (27.8 m/s; +641 %
//     before RopeWorld::addFastBodies paired the box a substep early). The trial is now solved once
//     more with the stretching relinearised about it, after the contact's active set (RopeObject::
//     solveTrialWithContacts, docs/method.md §8); the test checks that this happened.
//   - RopeWoundTenTimesRoundASpinningCylinder: 30.2 m/s against the bound of 40.2. The bound does not
//     see the energy the rope starts with: the default rope (EI = 0.49 N m^2) coiled at 5.55 cm radius
//     holds 277 J of bending energy (278.5 J in all), which as kinetic energy of its 0.316 kg would
//     be an rms speed of 42.0 m/s; the steps dissipate most of it. The scene is driven, so its energy
//     is not bounded: it peaks at 594 J (2.1 times the start) in one substep. Before the relinearised
//     contact trial its peak was 2,011 J, in substep 67, where the one-pass step in contact made
//     1,928 J of stretching from 35 J; relinearising in every active-set pass instead ran away (6.3 MJ
//     within five substeps; with a frictionless drum either way kept the start's energy). Parts of
//     the rope pass 15 cm into the drum (not asserted).
//   - StiffThinRopeAtASixtiethOfASecond (E = 1e13 Pa, r = 0.5 mm, h = 1/60 s) gained 2.4 % in its
//     first step and crept down at 0.1 m/s before the rod's second linearisation: now no growth,
//     0.28 m/s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "bullet_bridge/detail/bullet_math.h"
#include "bullet_bridge/rope_object.h"
#include "demos/scenes/physics_world.h"
#include "rope/common/error.h"
#include "rope/rod/rod.h"

namespace rope {
namespace {

constexpr double kG = 9.81;             // m/s^2, the worlds' gravity
constexpr double kSpeedFactor = 2.0;    // on v_driver + g T
constexpr double kEnergyGrowth = 0.01;  // of the starting total, undriven scenes only

bool finiteState(const Rod& rod) {
  for (const PointList* list : {&rod.controlPoints(), &rod.velocities()})
    for (const Vec3& p : *list)
      if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) return false;
  return true;
}

// Kinetic and gravitational energy of a dynamic body (0 for static and kinematic ones), J; the
// gravitational datum is y = 0.
double bodyEnergy(const btRigidBody& body) {
  if (body.getInvMass() == 0) return 0.0;
  const double mass = 1.0 / static_cast<double>(body.getInvMass());
  const btVector3 w = body.getAngularVelocity();
  const btVector3 iw = body.getInvInertiaTensorWorld().inverse() * w;
  return 0.5 * mass * static_cast<double>(body.getLinearVelocity().length2()) + 0.5 * static_cast<double>(w.dot(iw)) +
         mass * kG * static_cast<double>(body.getCenterOfMassPosition().y());
}

struct ExtremeRun {
  std::string name;
  double h = 1.0 / 240.0;  // s, one Bullet substep per step
  double duration = 1.0;   // s (T)
  double driverSpeed = 0;  // m/s, the fastest driver (a kinematic body, a moving box's initial speed)
  bool driven = false;     // true: no energy bound
  std::function<void(double time, double h)> drive = [](double, double) {};
};

struct ExtremeFigures {
  double fastest = 0.0;  // m/s
  double bound = 0.0;    // m/s
  double energyGrowth = 0.0;  // (highest - start) / |start|
  long failedSteps = 0;
  long relinearisedSubsteps = 0;  // RopeStepRecord::contactRelinearised, over the ropes
  double deepest = 0.0;  // m, deepest rope-body contact at the start of a substep
};

void runExtreme(demos::PhysicsWorld& physics, const std::vector<bullet::RopeObject*>& ropes, const ExtremeRun& run,
                ExtremeFigures& figures) {
  figures.bound = kSpeedFactor * (run.driverSpeed + kG * run.duration);
  const auto energy = [&] {
    double total = 0.0;
    for (const bullet::RopeObject* rope : ropes) total += rope->rod().totalEnergy();
    const btCollisionObjectArray& objects = physics.world().getCollisionObjectArray();
    for (int i = 0; i < objects.size(); ++i)
      if (const btRigidBody* body = btRigidBody::upcast(objects[i])) total += bodyEnergy(*body);
    return total;
  };
  const double start = energy();
  double highest = start;
  const int steps = static_cast<int>(std::lround(run.duration / run.h));
  for (int step = 0; step < steps; ++step) {
    run.drive(step * run.h, run.h);
    ASSERT_NO_THROW(physics.world().stepSimulation(btScalar(run.h), 1, btScalar(run.h))) << run.name << " step " << step;
    for (const bullet::RopeObject* rope : ropes) {
      ASSERT_TRUE(finiteState(rope->rod())) << run.name << " step " << step;
      for (const Vec3& v : rope->rod().velocities()) figures.fastest = std::max(figures.fastest, v.norm());
      figures.deepest = std::max(figures.deepest, rope->lastStep().maxPenetration);
      if (rope->lastStep().contactRelinearised) ++figures.relinearisedSubsteps;
    }
    highest = std::max(highest, energy());
  }
  long putToRest = 0;
  for (const bullet::RopeObject* rope : ropes) {
    figures.failedSteps += rope->warnings().failedSteps;
    putToRest += rope->warnings().timesPutToRest;
  }
  figures.energyGrowth = (highest - start) / std::abs(start);
  std::printf("%s: fastest rope point %.3g m/s (bound %.3g), energy growth %.3g %s, %ld failed substeps, deepest "
              "contact %.3g m, %ld contact trials relinearised\n",
              run.name.c_str(), figures.fastest, figures.bound, figures.energyGrowth,
              run.driven ? "(driven: not bounded)" : "of the start", figures.failedSteps, figures.deepest,
              figures.relinearisedSubsteps);
  EXPECT_LT(figures.fastest, figures.bound) << run.name;
  // A rope frozen after failing (RopeObject::kFailuresBeforeRest) cannot explode, but it has not
  // survived the scene either.
  EXPECT_EQ(putToRest, 0) << run.name << ": the rope failed until it was put to rest";
  if (!run.driven) {
    EXPECT_LE(figures.energyGrowth, kEnergyGrowth) << run.name;
  }
}

// A kinematic box, moved by the test (Bullet derives its velocity from the move).
btRigidBody* kinematicBody(btRigidBody* body) {
  body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  body->setActivationState(DISABLE_DEACTIVATION);
  return body;
}

void moveBy(btRigidBody& body, const btVector3& move) {
  btTransform transform = body.getWorldTransform();
  transform.setOrigin(transform.getOrigin() + move);
  body.setWorldTransform(transform);
}

TEST(Extremes, RopeSqueezedBetweenTwoBoxesDrivenTogether) {
  demos::PhysicsWorld physics;
  physics.addGround();
  const RodSettings rod;
  const double r = rod.radius;
  bullet::RopeObject rope(Rod::fromSegment(rod, Vec3(-0.5, r, 0), Vec3(0.5, r, 0)));
  physics.ropes().addRope(rope);
  // Two walls 1.2 m long and 0.1 m high, 1 cm clear of the rope on each side, driven together at
  // 5 cm/s until their gap is half the rope's diameter, then held.
  const double half = 0.05, speed = 0.05, start = half + r + 0.01, end = half + 0.5 * r;
  btRigidBody* walls[2];
  for (int i = 0; i < 2; ++i) {
    const double side = i == 0 ? -1.0 : 1.0;
    walls[i] = kinematicBody(physics.addBox(btVector3(0.6, btScalar(half), btScalar(half)), 0.0,
                                            btVector3(0, btScalar(half), btScalar(side * start))));
  }
  ExtremeRun run;
  run.name = "squeezed between two boxes";
  run.duration = 1.5;
  run.driverSpeed = speed;
  run.driven = true;
  run.drive = [&](double time, double h) {
    if (time + h > (start - end) / speed) return;
    for (int i = 0; i < 2; ++i) moveBy(*walls[i], btVector3(0, 0, btScalar((i == 0 ? 1.0 : -1.0) * speed * h)));
  };
  ExtremeFigures figures;
  runExtreme(physics, {&rope}, run, figures);
}

TEST(Extremes, RopeUnderAThousandKilogramBox) {
  demos::PhysicsWorld physics;
  physics.addGround();
  const RodSettings rod;
  const double r = rod.radius;
  bullet::RopeObject rope(Rod::fromSegment(rod, Vec3(-0.5, r, 0), Vec3(0.5, r, 0)));
  physics.ropes().addRope(rope);
  // A 0.5 m steel-like cube (8000 kg/m^3) released 2 mm above the rope, across it.
  physics.addBox(btVector3(0.25, 0.25, 0.25), 1000.0, btVector3(0, btScalar(2 * r + 0.002 + 0.25), 0));
  ExtremeRun run;
  run.name = "under a 1000 kg box";
  run.duration = 2.0;
  ExtremeFigures figures;
  runExtreme(physics, {&rope}, run, figures);
}

TEST(Extremes, StiffThinRopeAtASixtiethOfASecond) {
  demos::PhysicsWorld physics;
  physics.addGround();
  RodSettings rod;
  rod.youngsModulus = 1e13;  // Pa
  rod.radius = 5e-4;         // m
  bullet::RopeObject rope(Rod::fromSegment(rod, Vec3(0, 1.2, 0), Vec3(1, 1.2, 0)));
  physics.ropes().addRope(rope);
  rope.attachToPoint(rope.rod().beginParameter(), btVector3(0, btScalar(1.2), 0));
  ExtremeRun run;
  run.name = "E = 1e13 Pa, r = 0.5 mm, h = 1/60 s";
  run.h = 1.0 / 60.0;
  run.duration = 2.0;
  ExtremeFigures figures;
  runExtreme(physics, {&rope}, run, figures);
}

TEST(Extremes, RopeHitByAFiftyMetrePerSecondBox) {
  demos::PhysicsWorld physics;
  physics.addGround();
  const RodSettings rod;
  bullet::RopeObject rope(Rod::fromSegment(rod, Vec3(-0.5, 1, 0), Vec3(0.5, 1, 0)));
  physics.ropes().addRope(rope);
  rope.attachToPoint(rope.rod().beginParameter(), btVector3(-0.5, 1, 0));
  rope.attachToPoint(rope.rod().endParameter(), btVector3(0.5, 1, 0));
  // 2 kg, 0.3 m deep along its flight: deeper than its 0.21 m travel per substep, so it cannot pass
  // the rope between two substeps without overlapping it.
  btRigidBody* box = physics.addBox(btVector3(0.1, 0.1, 0.15), 2.0, btVector3(0, 1, -0.5));
  box->setLinearVelocity(btVector3(0, 0, 50));
  ExtremeRun run;
  run.name = "hit by a 50 m/s box";
  run.duration = 0.5;
  run.driverSpeed = 50.0;
  ExtremeFigures figures;
  runExtreme(physics, {&rope}, run, figures);
  // The impact's trial was solved again about itself (the one-pass trial made the energy +61 %).
  EXPECT_GT(figures.relinearisedSubsteps, 0);
}

TEST(Extremes, RopeWoundTenTimesRoundASpinningCylinder) {
  demos::PhysicsWorld physics;
  physics.addGround();
  RodSettings rod;
  const double r = rod.radius, cylinder = 0.05, omega = 10.0;  // m, m, rad/s
  const double helix = cylinder + r + 5e-4, pitch = 4.0 * r, turns = 10.0, centreY = 0.5;
  PointList points;
  const int perTurn = 12;
  for (int i = 0; i <= static_cast<int>(turns) * perTurn; ++i) {
    const double angle = 2.0 * M_PI * i / perTurn;
    points.emplace_back(helix * std::cos(angle), centreY + helix * std::sin(angle), -0.5 * turns * pitch + pitch * angle / (2.0 * M_PI));
  }
  bullet::RopeObject rope(Rod::fromPolyline(rod, points, Rod::RestShape::kAsGiven));
  physics.ropes().addRope(rope);
  btRigidBody* drum = kinematicBody(physics.addBody(
      std::make_unique<btCylinderShapeZ>(btVector3(btScalar(cylinder), btScalar(cylinder), 0.2)), 0.0,
      btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(centreY), 0))));
  ExtremeRun run;
  run.name = "wound ten times round a spinning cylinder";
  run.duration = 2.0;
  run.driverSpeed = omega * cylinder;
  run.driven = true;
  run.drive = [&](double, double h) {
    btTransform transform = drum->getWorldTransform();
    transform.setRotation(transform.getRotation() * btQuaternion(btVector3(0, 0, 1), btScalar(omega * h)));
    drum->setWorldTransform(transform);
  };
  ExtremeFigures figures;
  runExtreme(physics, {&rope}, run, figures);
  std::printf("  %d control points at the end\n", rope.rod().controlPointCount());
}

TEST(Extremes, ThousandRandomKnotInsertionsAndRemovalsDuringASwing) {
  RodSettings settings;
  settings.adaptive = false;  // only the random edits change the knots
  Rod rod = Rod::fromSegment(settings, Vec3(0, 1, 0), Vec3(1, 1, 0));
  rod.pin(0.0);
  const double g = 9.81, length = rod.restLength();
  const double scale = rod.mass() * g * length;
  const double speedBound = 1.5 * std::sqrt(2.0 * g * length);
  const double start = rod.totalEnergy();
  std::mt19937_64 random(17);  // raw outputs only: their sequence is fixed by the standard
  int insertions = 0, removals = 0;
  double highest = start, fastest = 0.0;
  for (int step = 0; step < 2400 && insertions + removals < 2000; ++step) {
    if (random() % 2 == 0) {
      const double s = rod.beginParameter() + (rod.endParameter() - rod.beginParameter()) * ((random() >> 11) * 0x1.0p-53);
      try {
        rod.insertKnot(s);
        ++insertions;
      } catch (const InvalidArgument&) {
        // too close to a knot, or at full multiplicity: refused, nothing changed
      }
    } else {
      const int interior = rod.knots().size() - 2 * (rod.degree() + 1);
      if (interior > 0) {
        rod.removeKnot(rod.knots()[rod.degree() + 1 + static_cast<int>(random() % static_cast<unsigned>(interior))]);
        ++removals;
      }
    }
    const StepReport report = rod.step(1.0 / 240.0);
    ASSERT_TRUE(report.ok) << "step " << step << ": " << report.failure;
    highest = std::max(highest, rod.totalEnergy());
    for (const Vec3& v : rod.velocities()) fastest = std::max(fastest, v.norm());
  }
  std::printf("knot edits during a swing: %d insertions, %d removals, energy growth %.3g of m g L, fastest %.3f m/s "
              "(bound %.3f)\n", insertions, removals, (highest - start) / scale, fastest, speedBound);
  EXPECT_GE(insertions, 500);
  EXPECT_GE(removals, 500);
  EXPECT_LE(highest - start, 0.01 * scale);
  EXPECT_LT(fastest, speedBound);
}

}  // namespace
}  // namespace rope
