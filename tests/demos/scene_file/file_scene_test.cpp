// SPDX-License-Identifier: MIT
// FileScene (demos/scene_file/file_scene.h): what its scripted events do to the world, against
// analytic values.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>

#include "demos/scene_file/file_scene.h"
#include "demos/scene_file/scene_file_reader.h"

namespace rope::demos {
namespace {

// A 1 m rope in zero gravity (nothing else acts on it) under a distributed force of q N/m over
// [s0, s1] for the first 0.1 s: its momentum is q (s1 - s0) t while the force acts (the consistent
// generalised forces of a distributed load sum to its resultant) and stays there after. Adaptivity is
// off: with it the rope's 16 control points drop to 7 by knot removals, which approximate the
// velocities within removalVelocityErrorBound and moved the momentum by 6e-5 of itself here
// (measured), not what this test is about.
TEST(FileSceneEvents, DistributedForceGivesItsResultantsImpulse) {
  const std::string text = R"({"gravity": [0, 0, 0], "timeStep": 0.01,
    "ropes": [{"name": "rope", "settings": {"gravity": [0, 0, 0], "adaptive": false},
               "shape": {"type": "segment", "from": [0, 0, 0], "to": [1, 0, 0]}}],
    "events": [{"type": "distributedForce", "time": 0, "until": 0.1, "rope": "rope", "s0": 0.25, "s1": 0.75,
                "forcePerLength": [0, 2, 0]}]})";
  FileScene scene(readSceneText(text));
  const bullet::RopeObject& rope = *scene.findRope("rope");
  for (int i = 0; i < 10; ++i) scene.step();
  const double impulse = 2.0 * 0.5 * 0.1;  // q (s1 - s0) t, N s
  EXPECT_NEAR(rope.rod().momentum().y(), impulse, 1e-12);
  EXPECT_NEAR(rope.rod().momentum().x(), 0.0, 1e-12);
  for (int i = 0; i < 10; ++i) scene.step();
  EXPECT_NEAR(rope.rod().momentum().y(), impulse, 1e-12) << "the force ends at 'until'";
}

// Left out, s0 and s1 are the rope's ends: the whole rope is pulled.
TEST(FileSceneEvents, DistributedForceDefaultsToTheWholeRope) {
  const std::string text = R"({"gravity": [0, 0, 0], "timeStep": 0.01,
    "ropes": [{"name": "rope", "settings": {"gravity": [0, 0, 0]},
               "shape": {"type": "segment", "from": [0, 0, 0], "to": [1, 0, 0]}}],
    "events": [{"type": "distributedForce", "time": 0.05, "until": 0.1, "rope": "rope", "forcePerLength": [0, 0, -3]}]})";
  FileScene scene(readSceneText(text));
  const bullet::RopeObject& rope = *scene.findRope("rope");
  for (int i = 0; i < 5; ++i) scene.step();
  EXPECT_EQ(rope.rod().momentum().z(), 0.0) << "not before 'time'";
  for (int i = 0; i < 10; ++i) scene.step();
  EXPECT_NEAR(rope.rod().momentum().z(), -3.0 * rope.rod().restLength() * 0.05, 1e-12);
}

// Keyframes: linear or smoothstep from one to the next, held outside them.
TEST(FileSceneKeyframes, LinearAndSmoothstep) {
  Keyframe a, b;
  a.time = 1.0;
  a.position = Vec3(0.0, 2.0, 0.0);
  b.time = 3.0;
  b.position = Vec3(4.0, 2.0, 0.0);
  b.rotation = Eigen::Vector4d(0.0, std::sqrt(0.5), 0.0, std::sqrt(0.5));  // 90 degrees about y
  const std::vector<Keyframe> linear = {a, b};
  EXPECT_EQ(keyframePose(linear, 0.0).getOrigin().x(), 0.0) << "held before the first";
  EXPECT_EQ(keyframePose(linear, 1.5).getOrigin().x(), 1.0);  // u = 1/4
  EXPECT_EQ(keyframePose(linear, 9.0).getOrigin().x(), 4.0) << "held after the last";
  a.interpolation = Keyframe::Interpolation::kSmoothstep;
  const std::vector<Keyframe> smooth = {a, b};
  EXPECT_EQ(keyframePose(smooth, 1.5).getOrigin().x(), 4.0 * 0.15625);  // u^2 (3 - 2u) at u = 1/4
  EXPECT_EQ(keyframePose(smooth, 2.0).getOrigin().x(), 2.0);            // symmetric: half way at u = 1/2
  EXPECT_EQ(keyframePose(smooth, 2.5).getOrigin().x(), 4.0 * 0.84375);
  EXPECT_EQ(keyframePose(smooth, 3.0).getOrigin().x(), 4.0);
  // Rotations are eased alike: a quarter of the way in time is 0.15625 of the 90 degrees.
  const btQuaternion q = keyframePose(smooth, 1.5).getRotation();
  EXPECT_NEAR(2.0 * std::atan2(static_cast<double>(q.y()), static_cast<double>(q.w())), 0.15625 * 0.5 * 3.14159265358979323846, 1e-12);
  // Zero velocity at both ends: the position moves by O(dt^2) in the first and last dt.
  const double dt = 1e-4;
  EXPECT_LT(keyframePose(smooth, 1.0 + dt).getOrigin().x(), 4.0 * 3.0 * (dt / 2.0) * (dt / 2.0) * 1.0001);
  EXPECT_GT(keyframePose(smooth, 3.0 - dt).getOrigin().x(), 4.0 - 4.0 * 3.0 * (dt / 2.0) * (dt / 2.0) * 1.0001);
}

// A body's own gravity, ramped up over gravityRampTime: each step takes its value at the step's end,
// so with symplectic Euler v_n = h sum_k g min(1, k h / T): after 20 steps of 0.01 s with T = 0.1 s,
// 2 m/s^2 x 0.01 s x (5.5 + 10) = 0.31 m/s; the world's gravity does not act on it.
TEST(FileSceneBodies, OwnGravityRampsUpAndReplacesTheWorlds) {
  const std::string text = R"({"timeStep": 0.01,
    "bodies": [{"name": "load", "shape": "sphere", "radius": 0.05, "motion": "dynamic", "mass": 0.7,
                "gravity": [2, 0, 0], "gravityRampTime": 0.1}]})";
  FileScene scene(readSceneText(text));
  const btRigidBody& load = *scene.findBody("load");
  scene.step();
  EXPECT_NEAR(load.getGravity().x(), 0.2, 1e-15) << "a tenth of the way up the ramp after the first step";
  for (int i = 1; i < 20; ++i) scene.step();
  EXPECT_NEAR(load.getLinearVelocity().x(), 0.31, 1e-12);
  EXPECT_EQ(load.getLinearVelocity().y(), 0.0);
  EXPECT_EQ(load.getGravity().x(), 2.0);
}

// `axis` picks Bullet's cylinder and capsule along x, y or z.
TEST(FileSceneBodies, CylinderAndCapsuleAxes) {
  const std::string text = R"({"bodies": [
    {"name": "x", "shape": "cylinder", "axis": "x", "halfExtents": [0.3, 0.1, 0.1]},
    {"name": "y", "shape": "cylinder", "halfExtents": [0.1, 0.3, 0.1], "position": [1, 0, 0]},
    {"name": "z", "shape": "capsule", "axis": "z", "radius": 0.1, "height": 0.4, "position": [2, 0, 0]}]})";
  FileScene scene(readSceneText(text));
  const auto* x = dynamic_cast<const btCylinderShape*>(scene.findBody("x")->getCollisionShape());
  const auto* y = dynamic_cast<const btCylinderShape*>(scene.findBody("y")->getCollisionShape());
  const auto* z = dynamic_cast<const btCapsuleShape*>(scene.findBody("z")->getCollisionShape());
  ASSERT_TRUE(x && y && z);
  EXPECT_EQ(x->getUpAxis(), 0);
  EXPECT_EQ(y->getUpAxis(), 1);
  EXPECT_EQ(z->getUpAxis(), 2);
  EXPECT_NEAR(x->getHalfExtentsWithMargin().x(), 0.3, 1e-12);  // the half length, along the axis
  EXPECT_NEAR(z->getHalfHeight(), 0.2, 1e-12);
}

}  // namespace
}  // namespace rope::demos
