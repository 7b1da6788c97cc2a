// SPDX-License-Identifier: MIT
// Every check kind of a scene file on a scene built to pass it and on one built to fail it, with
// the worst value and its time against a value measured independently in the test (or known
// analytically: a falling sphere, a kinematic probe dragged along a rope).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <string>

#include "demos/scene_file/file_scene.h"
#include "demos/scene_file/scene_file_reader.h"
#include "demos/scenes/knot_scene.h"

namespace rope::demos {
namespace {

constexpr double kH = 1.0 / 240.0;

const CheckResult& result(const FileScene& scene, const std::string& name) {
  for (const CheckResult& check : scene.checks().results()) {
    if (check.name == name) return check;
  }
  throw std::runtime_error("no check " + name);
}

// Runs the scene for `steps` steps; `observe` sees it after each one.
void run(FileScene& scene, long steps, const std::function<void(const FileScene&)>& observe = {}) {
  for (long i = 0; i < steps; ++i) {
    scene.step();
    if (observe) observe(scene);
  }
  scene.finishChecks();
}

// The largest value of a series and the first time it was reached.
struct Extreme {
  double value = -1e300;
  double time = 0.0;
  void add(double v, double t) {
    if (v > value) value = v, time = t;
  }
};

// A 1 kg box hanging on a 1 m rope pinned at its top (a held winch there too); settles in ~2 s.
const char* kHangingBox = R"({
  "duration": 3.0,
  "bodies": [{"name": "box", "shape": "box", "halfExtents": [0.05, 0.05, 0.05], "motion": "dynamic", "mass": 1.0,
              "position": [0, -0.05, 0]}],
  "ropes": [{"name": "rope", "settings": {"massDamping": 2.0},
             "shape": {"type": "segment", "from": [0, 1, 0], "to": [0, 0, 0]},
             "pins": [{"name": "top", "s": "begin"}],
             "attachments": [{"name": "hook", "s": "end", "body": "box", "localPoint": [0, 0.05, 0]}],
             "winches": [{"end": "begin", "speed": 0.0}]}],
  "checks": [
    {"name": "hook holds the weight", "type": "tension", "rope": "rope", "attachment": "hook", "min": 9.0, "max": 10.5, "from": 2.0},
    {"name": "hook tension below 9 N", "type": "tension", "rope": "rope", "attachment": "hook", "max": 9.0, "from": 2.0},
    {"name": "winch holds the weight", "type": "tension", "rope": "rope", "winch": "begin", "min": 10.2, "max": 11.2, "from": 2.0},
    {"name": "winch tension above 11.5 N", "type": "tension", "rope": "rope", "winch": "begin", "min": 11.5, "from": 2.0},
    {"name": "middle holds the weight", "type": "tension", "rope": "rope", "s": 0.5, "min": 9.8, "max": 10.8, "from": 2.0},
    {"name": "middle below 5 N", "type": "tension", "rope": "rope", "s": 0.5, "max": 5.0, "from": 2.0},
    {"name": "box hangs below the pin", "type": "position", "body": "box", "at": 3.0, "target": [0, -0.05, 0], "max": 0.01},
    {"name": "box has risen to the pin", "type": "position", "body": "box", "at": 3.0, "box": {"min": [-1, 0.9, -1], "max": [1, 1.1, 1]}},
    {"name": "rope end stays at the box", "type": "position", "rope": "rope", "s": "end", "from": 2.0, "target": [0, 0, 0], "max": 0.01},
    {"name": "no warnings", "type": "health"}
  ]})";

TEST(SceneChecks, TensionAtAnAttachmentAWinchAndAParameter) {
  FileScene scene(readSceneText(kHangingBox));
  Extreme hook, winch, middle;
  double winchLow = 1e300, winchLowTime = 0.0;
  run(scene, 720, [&](const FileScene& s) {
    if (s.time() < 2.0 - 0.5 * kH) return;
    const bullet::RopeObject& rope = *s.findRope("rope");
    const double a = rope.attachmentTension(*s.attachmentId("rope", "hook"));
    const double w = rope.winchTension(bullet::RopeEnd::kBegin);
    hook.add(a, s.time());
    winch.add(w, s.time());
    middle.add(rope.tension(0.5), s.time());
    if (w < winchLow) winchLow = w, winchLowTime = s.time();
  });
  // The box's weight (9.81 N) plus the rope's below the point (1150 kg/m^3 * pi (5 mm)^2 =
  // 0.0903 kg/m): statics, to 2 % (the largest value over the window: the box still bounces a little).
  const double ropeWeight = 1150.0 * 3.14159265358979 * 0.005 * 0.005 * 9.81;
  EXPECT_NEAR(hook.value, 9.81, 0.2);
  EXPECT_NEAR(winch.value, 9.81 + ropeWeight, 0.2);
  EXPECT_NEAR(middle.value, 9.81 + 0.5 * ropeWeight, 0.2);

  EXPECT_TRUE(result(scene, "hook holds the weight").passed);
  const CheckResult& hookFails = result(scene, "hook tension below 9 N");
  EXPECT_FALSE(hookFails.passed);
  EXPECT_DOUBLE_EQ(hookFails.worst, hook.value);
  EXPECT_DOUBLE_EQ(hookFails.worstTime, hook.time);
  EXPECT_EQ(hookFails.samples, 241);

  EXPECT_TRUE(result(scene, "winch holds the weight").passed);
  const CheckResult& winchFails = result(scene, "winch tension above 11.5 N");
  EXPECT_FALSE(winchFails.passed);
  EXPECT_DOUBLE_EQ(winchFails.worst, winchLow);  // a lower bound: the worst is the smallest value
  EXPECT_DOUBLE_EQ(winchFails.worstTime, winchLowTime);

  EXPECT_TRUE(result(scene, "middle holds the weight").passed);
  const CheckResult& middleFails = result(scene, "middle below 5 N");
  EXPECT_FALSE(middleFails.passed);
  EXPECT_DOUBLE_EQ(middleFails.worst, middle.value);
  EXPECT_DOUBLE_EQ(middleFails.worstTime, middle.time);

  EXPECT_TRUE(result(scene, "box hangs below the pin").passed);
  const CheckResult& risen = result(scene, "box has risen to the pin");
  EXPECT_FALSE(risen.passed);
  EXPECT_EQ(risen.samples, 1);  // one time: the step that ends at 3 s
  EXPECT_NEAR(risen.worstTime, 3.0, 1e-9);
  const btVector3 box = scene.findBody("box")->getWorldTransform().getOrigin();
  EXPECT_NEAR(risen.worst, 0.9 - box.y(), 1e-12);  // distance below the box's floor
  EXPECT_TRUE(result(scene, "rope end stays at the box").passed);
  EXPECT_TRUE(result(scene, "no warnings").passed);
}

TEST(SceneChecks, PositionOfAFallingSphereMatchesSymplecticEuler) {
  // No ropes, no contact: Bullet's semi-implicit Euler gives y_n = y_0 - g h^2 n (n + 1) / 2 exactly
  // (up to round-off).
  FileScene scene(readSceneText(R"({
    "bodies": [{"name": "ball", "shape": "sphere", "radius": 0.1, "motion": "dynamic", "mass": 2.0, "position": [0, 10, 0]}],
    "checks": [
      {"name": "ball is near its analytic place", "type": "position", "body": "ball", "at": 0.5, "target": [0, 8.77375, 0], "max": 0.02},
      {"name": "ball has not fallen", "type": "position", "body": "ball", "from": 0.25, "to": 0.5, "target": [0, 10, 0], "max": 0.1},
      {"name": "ball stays in its box", "type": "position", "body": "ball", "box": {"min": [-1, 9.5, -1], "max": [1, 11, 1]}}
    ]})"));
  run(scene, 150);
  const auto analytic = [](long n) { return 10.0 - 9.81 * kH * kH * n * (n + 1) / 2.0; };
  EXPECT_TRUE(result(scene, "ball is near its analytic place").passed);
  EXPECT_NEAR(result(scene, "ball is near its analytic place").worst, std::abs(analytic(120) - 8.77375), 1e-9);
  const CheckResult& fallen = result(scene, "ball has not fallen");
  EXPECT_FALSE(fallen.passed);
  EXPECT_NEAR(fallen.worst, 10.0 - analytic(120), 1e-9);  // the end of the window is the worst
  EXPECT_NEAR(fallen.worstTime, 0.5, 1e-9);
  const CheckResult& box = result(scene, "ball stays in its box");
  EXPECT_FALSE(box.passed);
  EXPECT_NEAR(box.worst, 9.5 - analytic(150), 1e-9);
  EXPECT_NEAR(box.worstTime, 150 * kH, 1e-9);
}

TEST(SceneChecks, SlipOfAProbeDraggedAlongARope) {
  // A kinematic probe 10 cm above a straight weightless rope pinned at both ends, moved 0.2 m
  // along it over 1 s: it slips 0.2 m along the rope less the first step's 0.2 h (the window's
  // first step is its reference), reached at 1 s.
  FileScene scene(readSceneText(R"({
    "gravity": [0, 0, 0],
    "bodies": [{"name": "probe", "shape": "sphere", "radius": 0.02, "motion": "kinematic",
                "keyframes": [{"time": 0, "position": [0, 0.1, 0]}, {"time": 1, "position": [0.2, 0.1, 0]}]}],
    "ropes": [{"name": "rope", "shape": {"type": "segment", "from": [-0.5, 0, 0], "to": [0.5, 0, 0]},
               "pins": [{"s": "begin"}, {"s": "end"}]}],
    "checks": [
      {"name": "slips less than 0.25 m", "type": "slip", "rope": "rope", "body": "probe", "max": 0.25},
      {"name": "slips less than 0.1 m", "type": "slip", "rope": "rope", "body": "probe", "max": 0.1},
      {"name": "probe never touches the rope", "type": "contact", "rope": "rope", "body": "probe", "mode": "never"}
    ]})"));
  run(scene, 288);
  EXPECT_TRUE(result(scene, "slips less than 0.25 m").passed);
  const CheckResult& slip = result(scene, "slips less than 0.1 m");
  EXPECT_FALSE(slip.passed);
  EXPECT_NEAR(slip.worst, 0.2 - 0.2 * kH, 1e-6);
  EXPECT_NEAR(slip.worstTime, 1.0, 0.5 * kH);
  EXPECT_TRUE(result(scene, "probe never touches the rope").passed);
}

TEST(SceneChecks, ContactAndPenetrationOfARopeOnABox) {
  // A straight rope dropped 5 cm onto a box: it never touches the ground plane below the box, it
  // touches the box from its landing on, and its deepest penetration is the impact's.
  FileScene scene(readSceneText(R"({
    "bodies": [{"name": "ground", "shape": "plane", "offset": -1.0},
               {"name": "box", "shape": "box", "halfExtents": [1, 0.1, 0.5], "position": [0, -0.1, 0]}],
    "ropes": [{"name": "rope", "shape": {"type": "segment", "from": [-0.5, 0.055, 0], "to": [0.5, 0.055, 0]}}],
    "checks": [
      {"name": "never touches the ground", "type": "contact", "rope": "rope", "body": "ground", "mode": "never"},
      {"name": "never touches the box", "type": "contact", "rope": "rope", "body": "box", "mode": "never"},
      {"name": "stays on the box", "type": "contact", "rope": "rope", "body": "box", "mode": "stays", "from": 0.5},
      {"name": "stays on the box from the start", "type": "contact", "rope": "rope", "body": "box", "mode": "stays"},
      {"name": "shallow", "type": "penetration", "rope": "rope", "body": "box", "max": 0.005},
      {"name": "no deeper than 1 um", "type": "penetration", "rope": "rope", "max": 1e-6}
    ]})"));
  Extreme depth, contacts;
  double firstContact = -1.0, firstDeep = -1.0;
  btVector3 firstDeepPoint(0, 0, 0);
  run(scene, 240, [&](const FileScene& s) {
    double deepest = 0.0;
    int count = 0;
    for (const bullet::RopeContactRecord& contact : s.findRope("rope")->contacts()) {
      if (!contact.active) continue;
      if (contact.depth > deepest) {
        deepest = contact.depth;
        if (firstDeep < 0.0 && deepest > 1e-6) firstDeepPoint = contact.point;
      }
      ++count;
    }
    if (firstDeep < 0.0 && deepest > 1e-6) firstDeep = s.time();
    depth.add(deepest, s.time());
    contacts.add(count, s.time());
    if (count > 0 && firstContact < 0.0) firstContact = s.time();
  });
  EXPECT_TRUE(result(scene, "never touches the ground").passed);
  const CheckResult& never = result(scene, "never touches the box");
  EXPECT_FALSE(never.passed);
  EXPECT_EQ(never.worst, contacts.value);
  EXPECT_DOUBLE_EQ(never.worstTime, contacts.time);
  EXPECT_TRUE(result(scene, "stays on the box").passed);
  const CheckResult& fromStart = result(scene, "stays on the box from the start");
  EXPECT_FALSE(fromStart.passed);  // in the air for the first 0.1 s
  EXPECT_EQ(fromStart.worst, 0.0);
  EXPECT_NEAR(fromStart.worstTime, kH, 1e-12);
  EXPECT_GT(firstContact, 0.05);  // free fall of 5 cm: 0.1 s
  EXPECT_TRUE(result(scene, "shallow").passed);
  const CheckResult& deep = result(scene, "no deeper than 1 um");
  EXPECT_FALSE(deep.passed);
  EXPECT_DOUBLE_EQ(deep.worst, depth.value);
  EXPECT_DOUBLE_EQ(deep.worstTime, depth.time);
  EXPECT_GT(deep.worst, 1e-6);
  // Its first failure, and the contact a snapshot marks: the deepest one of that step.
  EXPECT_DOUBLE_EQ(deep.firstFailureTime, firstDeep);
  EXPECT_EQ(deep.marker, Vec3(firstDeepPoint.x(), firstDeepPoint.y(), firstDeepPoint.z()));
  EXPECT_TRUE(std::isnan(result(scene, "shallow").firstFailureTime));
}

TEST(SceneChecks, HealthCountsFailedSteps) {
  // A pin dragged 80 m in one step: the rod's step fails from then on (the stretch bound), each
  // failure a warning.
  FileScene scene(readSceneText(R"({
    "gravity": [0, 0, 0],
    "ropes": [{"name": "rope", "shape": {"type": "segment", "from": [-0.5, 0, 0], "to": [0.5, 0, 0]},
               "pins": [{"s": "begin"}, {"s": "end", "keyframes": [{"time": 0.1, "position": [0.5, 0, 0]},
                                                                    {"time": 0.105, "position": [80, 0, 0]}]}]}],
    "checks": [
      {"name": "healthy before the jerk", "type": "health", "to": 0.09},
      {"name": "healthy", "type": "health", "rope": "rope"}
    ]})"));
  long failures = 0;
  double firstFailure = -1.0;
  run(scene, 120, [&](const FileScene& s) {
    if (!s.findRope("rope")->lastStep().ok) {
      ++failures;
      if (firstFailure < 0.0) firstFailure = s.time();
    }
  });
  EXPECT_TRUE(result(scene, "healthy before the jerk").passed);
  const CheckResult& health = result(scene, "healthy");
  EXPECT_FALSE(health.passed);
  EXPECT_GT(failures, 0);
  EXPECT_EQ(health.worst, static_cast<double>(scene.findRope("rope")->warnings().total()));
  EXPECT_EQ(health.worst, static_cast<double>(failures));
  EXPECT_NEAR(health.worstTime, 0.5, 1e-9);  // the count grows to the end
  EXPECT_NEAR(firstFailure, 0.1 + kH, 1e-9);
}

TEST(SceneChecks, KnotRegionLengthInThePile) {
  // The pile's coil lands after 0.3 s and its turns touch each other: the self-contact region
  // (knotRegion, as the knot scene measures it) grows.
  FileScene scene(readSceneText(R"({
    "bodies": [{"name": "ground", "shape": "plane"}],
    "ropes": [{"name": "rope",
               "settings": {"restLength": 2.0, "radius": 0.005, "youngsModulus": 1.0e8, "bendingStiffness": 1.0e-4,
                            "massDamping": 0.5, "stiffnessDamping": 0.01, "maxControlPoints": 128, "friction": 0.5477225575051661},
               "shape": {"type": "coil", "center": [0.0, 0.1, 0.0], "radius": 0.06, "pitch": 0.04, "tilt": 0.3}}],
    "checks": [
      {"name": "knot region under the rope length", "type": "knotLength", "rope": "rope", "max": 2.5},
      {"name": "knot region under 5 cm", "type": "knotLength", "rope": "rope", "max": 0.05}
    ]})"));
  Extreme length;
  run(scene, 120, [&](const FileScene& s) {
    const KnotRegion region = knotRegion(*s.findRope("rope"), s.physics().ropes().lastReport());
    length.add(region.found ? region.length : 0.0, s.time());
  });
  EXPECT_TRUE(result(scene, "knot region under the rope length").passed);
  const CheckResult& knot = result(scene, "knot region under 5 cm");
  EXPECT_FALSE(knot.passed);
  EXPECT_DOUBLE_EQ(knot.worst, length.value);
  EXPECT_DOUBLE_EQ(knot.worstTime, length.time);
  EXPECT_GT(knot.worst, 0.05);
}

TEST(SceneChecks, AWindowWithNoStepFails) {
  FileScene scene(readSceneText(R"({
    "bodies": [{"name": "ball", "shape": "sphere", "radius": 0.1, "motion": "dynamic", "mass": 1.0}],
    "checks": [{"name": "late", "type": "position", "body": "ball", "at": 100.0, "target": [0, 0, 0], "max": 1e9}]})"));
  run(scene, 10);
  const CheckResult& late = result(scene, "late");
  EXPECT_FALSE(late.passed);
  EXPECT_EQ(late.samples, 0);
  EXPECT_NE(late.message.find("not evaluated"), std::string::npos) << late.message;
}

}  // namespace
}  // namespace rope::demos

namespace rope::demos {
namespace {

// A 2 m x 0.2 m x 1 m slab as an OBJ file: 8 vertices, 6 quads (top face at y = 0).
std::string writeSlab(const std::string& name) {
  const std::string file = testing::TempDir() + "/" + name;
  std::ofstream obj(file);
  obj << "# slab\n";
  for (const int x : {-1, 1}) {
    for (const int y : {-2, 0}) {
      for (const int z : {-1, 1}) obj << "v " << x << " " << 0.1 * y << " " << 0.5 * z << "\n";
    }
  }
  // Vertex (x, y, z) index: 1 + 4 (x > 0) + 2 (y > -0.2) + (z > 0); faces wound outwards.
  obj << "f 1 2 4 3\nf 5 7 8 6\nf 1 5 6 2\nf 3 4 8 7\nf 1 3 7 5\nf 2 6 8 4\n";
  return file;
}

// A rope laid on the slab's top face stays there, one radius above it (to the resting depth, about
// half a micrometre: BulletRopeSettings::lineContactStiffness), whether Bullet sees the OBJ as a
// triangle mesh or as a convex hull (margin 0).
TEST(SceneFileMeshes, RopeRestsOnATriangleMeshAndAConvexHullFromObjFiles) {
  const std::string slab = writeSlab("slab.obj");
  for (const char* type : {"triangleMesh", "convexHull"}) {
    SCOPED_TRACE(type);
    FileScene scene(readSceneText(std::string(R"({
      "bodies": [{"name": "slab", "shape": "mesh", "mesh": ")") + slab + R"(", "meshType": ")" + type + R"("}],
      "ropes": [{"name": "rope", "shape": {"type": "segment", "from": [-0.5, 0.005, 0.013], "to": [0.5, 0.005, 0.013]}}],
      "checks": [{"name": "rests on the slab", "type": "contact", "rope": "rope", "body": "slab", "mode": "stays", "from": 0.5},
                 {"name": "shallow", "type": "penetration", "rope": "rope", "body": "slab", "max": 1e-5, "from": 0.5},
                 {"name": "one radius above the top face", "type": "position", "rope": "rope", "s": 0.5,
                  "target": [0, 0.005, 0.013], "max": 1e-5, "from": 0.5}]})"));
    run(scene, 240);
    for (const CheckResult& check : scene.checks().results()) EXPECT_TRUE(check.passed) << check.name << ": " << check.message;
    EXPECT_EQ(result(scene, "rests on the slab").samples, 121);
  }
}

}  // namespace
}  // namespace rope::demos

namespace rope::demos {
namespace {

// A world a user built in code, dumped with Bullet's own serializer: a static shelf (named) and an
// unnamed 1 kg ball above it.
std::string writeBulletWorld(const std::string& name) {
  PhysicsWorld world;
  btRigidBody* shelf = world.addBox(btVector3(1.0, 0.1, 0.5), 0.0, btVector3(0, -0.1, 0));
  world.addBody(std::make_unique<btSphereShape>(btScalar(0.05)), 1.0, btTransform(btQuaternion::getIdentity(), btVector3(0.8, 1.0, 0.3)));
  btDefaultSerializer serializer;
  serializer.registerNameForPointer(shelf, "shelf");
  world.world().serialize(&serializer);
  const std::string file = testing::TempDir() + "/" + name;
  std::ofstream(file, std::ios::binary)
      .write(static_cast<const char*>(static_cast<const void*>(serializer.getBufferPointer())), serializer.getCurrentBufferSize());
  return file;
}

TEST(SceneFileBulletWorld, RopeOnAShelfImportedFromABulletFile) {
  const std::string file = writeBulletWorld("cell.bullet");
  FileScene scene(readSceneText(R"({
    "bodies": [{"name": "cell", "shape": "bulletFile", "file": ")" + file + R"("}],
    "ropes": [{"name": "rope", "shape": {"type": "segment", "from": [-0.5, 0.005, 0.013], "to": [0.5, 0.005, 0.013]}}],
    "checks": [{"name": "rests on the shelf", "type": "contact", "rope": "rope", "body": "cell/shelf", "mode": "stays", "from": 0.5},
               {"name": "shallow", "type": "penetration", "rope": "rope", "body": "cell/shelf", "max": 1e-5, "from": 0.5},
               {"name": "one radius above the shelf", "type": "position", "rope": "rope", "s": 0.5,
                "target": [0, 0.005, 0.013], "max": 1e-5, "from": 0.5},
               {"name": "ball lands on the shelf", "type": "position", "body": "cell/body1", "at": 1.0,
                "target": [0.8, 0.05, 0.3], "max": 0.002}]})"));
  ASSERT_NE(scene.findBody("cell/shelf"), nullptr);
  ASSERT_NE(scene.findBody("cell/body1"), nullptr);
  EXPECT_EQ(scene.findBody("cell/shelf")->getWorldTransform().getOrigin(), btVector3(0, -0.1, 0));
  run(scene, 240);
  for (const CheckResult& check : scene.checks().results()) EXPECT_TRUE(check.passed) << check.name << ": " << check.message;
}

}  // namespace
}  // namespace rope::demos

namespace rope::demos {
namespace {

TEST(SceneFileEvents, ForceAndVelocityOnABodyFollowSymplecticEuler) {
  // Zero gravity. A 2 kg ball pushed by 4 N for 0.5 s (a = 2 m/s^2): after n steps x = a h^2 n (n+1)/2,
  // then it coasts at a h n. A second ball gets v = 3 m/s upwards at 0.25 s: 0.75 m by 0.5 s.
  FileScene scene(readSceneText(R"({
    "gravity": [0, 0, 0],
    "bodies": [{"name": "pushed", "shape": "sphere", "radius": 0.1, "motion": "dynamic", "mass": 2.0},
               {"name": "kicked", "shape": "sphere", "radius": 0.1, "motion": "dynamic", "mass": 1.0, "position": [0, 0, 5]}],
    "events": [{"type": "force", "body": "pushed", "force": [4, 0, 0], "time": 0.0, "until": 0.5},
               {"type": "velocity", "body": "kicked", "linearVelocity": [0, 3, 0], "time": 0.25}],
    "checks": [{"name": "pushed at 0.5 s", "type": "position", "body": "pushed", "at": 0.5, "target": [0.25208333333333333, 0, 0], "max": 1e-12},
               {"name": "coasting at 1 s", "type": "position", "body": "pushed", "at": 1.0, "target": [0.75208333333333333, 0, 0], "max": 1e-12},
               {"name": "kicked at 0.5 s", "type": "position", "body": "kicked", "at": 0.5, "target": [0, 0.75, 5], "max": 1e-12}]})"));
  run(scene, 240);
  for (const CheckResult& check : scene.checks().results()) {
    EXPECT_TRUE(check.passed) << check.name << ": " << check.message;
    EXPECT_EQ(check.samples, 1) << check.name;
  }
}

TEST(SceneFileEvents, ForceOnARopeAndTheReleaseOfItsPin) {
  // A weightless rope pinned at its beginning and pulled along itself at its end by 1 N: at rest the
  // tension is 1 N all along. Released at 1 s, it is dragged by the force against its mass damping
  // (a drag per unit mass), so at its terminal speed the tension falls linearly from 1 N at the end
  // to 0 at the free beginning: 0.5 N in the middle.
  FileScene scene(readSceneText(R"({
    "gravity": [0, 0, 0],
    "ropes": [{"name": "rope", "settings": {"massDamping": 20.0},
               "shape": {"type": "segment", "from": [0, 0, 0], "to": [1, 0, 0]},
               "pins": [{"name": "anchor", "s": "begin"}]}],
    "events": [{"type": "force", "rope": "rope", "s": "end", "force": [1, 0, 0], "time": 0.0, "until": 10.0},
               {"type": "release", "rope": "rope", "attachment": "anchor", "time": 1.0}],
    "checks": [{"name": "1 N along the pinned rope", "type": "tension", "rope": "rope", "s": 0.5, "min": 0.999, "max": 1.001, "from": 0.5, "to": 1.0},
               {"name": "0.5 N in the middle of the dragged rope", "type": "tension", "rope": "rope", "s": 0.5, "min": 0.499, "max": 0.501, "from": 2.0},
               {"name": "anchor holds until released", "type": "tension", "rope": "rope", "attachment": "anchor", "min": 0.999, "max": 1.001, "from": 0.5}]})"));
  run(scene, 600);
  for (const CheckResult& check : scene.checks().results()) EXPECT_TRUE(check.passed) << check.name << ": " << check.message;
  // The anchor's check ends with the anchor: measured only until the release.
  EXPECT_NEAR(result(scene, "anchor holds until released").samples, 120, 1);
  EXPECT_FALSE(scene.attachmentId("rope", "anchor").has_value());
}

}  // namespace
}  // namespace rope::demos
