// SPDX-License-Identifier: MIT
// FileScene (demos/scene_file/file_scene.h): what its scripted events do to the world, against
// analytic values.
#include <gtest/gtest.h>

#include <string>

#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>

#include "demos/scene_file/file_scene.h"
#include "demos/scene_file/scene_file_reader.h"

namespace rope::demos {
namespace {

// A 1 m rope in zero gravity (nothing else acts on it) under a distributed force of q N/m over
// [s0, s1] for the first 0.1 s: its momentum is q (s1 - s0) t while the force acts (the consistent
// generalised forces of a distributed load sum to its resultant) and stays there after. Adaptivity is
// off: the rope bends under the partial load, and a knot insertion re-fits the velocities, which moved
// the momentum by 6e-5 of itself here (measured), not what this test is about.
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
