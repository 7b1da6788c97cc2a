// SPDX-License-Identifier: MIT
// Debug drawing (bullet_bridge/rope_debug_draw.h) through Bullet's debugDrawWorld: the curve as a
// polyline, one capsule per proxy, one contact point per contact.
#include "bullet_bridge/rope_debug_draw.h"

#include <gtest/gtest.h>

#include "bullet_bridge/rope_world.h"
#include "demos/scenes/drape_scene.h"
#include "rope/common/error.h"

namespace rope::bullet {
namespace {

class RecordingDrawer : public btIDebugDraw {
 public:
  void drawLine(const btVector3& from, const btVector3& to, const btVector3& colour) override {
    ++lines;
    if (colour == RopeDebugColours().curve) {
      ++curveLines;
      curveLength += (to - from).length();
    }
  }
  void drawCapsule(btScalar radius, btScalar halfHeight, int, const btTransform&, const btVector3&) override {
    ++capsules;
    lastRadius = radius;
    capsuleLength += 2 * halfHeight;
  }
  void drawContactPoint(const btVector3&, const btVector3&, btScalar, int, const btVector3&) override { ++contacts; }
  void reportErrorWarning(const char*) override {}
  void draw3dText(const btVector3&, const char*) override {}
  void setDebugMode(int mode) override { mode_ = mode; }
  int getDebugMode() const override { return mode_; }

  int lines = 0, curveLines = 0, capsules = 0, contacts = 0;
  double curveLength = 0.0, capsuleLength = 0.0;
  btScalar lastRadius = 0;

 private:
  int mode_ = DBG_DrawWireframe | DBG_DrawContactPoints;
};

TEST(RopeDebugDraw, DrawsCurveCapsulesAndContactsThroughDebugDrawWorld) {
  demos::DrapeScene scene{demos::DrapeSceneSettings{}};
  for (int i = 0; i < 240; ++i) scene.step();  // resting on the box
  RecordingDrawer drawer;
  scene.physics().world().setDebugDrawer(&drawer);
  scene.physics().world().debugDrawWorld();
  scene.physics().world().setDebugDrawer(nullptr);
  const RopeObject& rope = scene.rope();
  EXPECT_EQ(drawer.capsules, rope.proxies().size());
  EXPECT_NEAR(drawer.lastRadius, rope.rod().settings().radius, 1e-7);  // btScalar
  EXPECT_EQ(drawer.contacts, static_cast<int>(rope.contacts().size()));
  EXPECT_GT(drawer.contacts, 0);
  EXPECT_NEAR(drawer.curveLength, rope.rod().length(), 1e-3);
  EXPECT_NEAR(drawer.capsuleLength, rope.rod().length(), 1e-3);
}

TEST(RopeDebugDraw, CanBeSwitchedOffAndRejectsBadInput) {
  demos::DrapeScene scene{demos::DrapeSceneSettings{}};
  scene.physics().ropes().setDebugDrawEnabled(false);
  RecordingDrawer drawer;
  scene.physics().world().setDebugDrawer(&drawer);
  scene.physics().world().debugDrawWorld();
  scene.physics().world().setDebugDrawer(nullptr);
  EXPECT_EQ(drawer.curveLines, 0);
  EXPECT_EQ(drawer.capsules, 0);
  EXPECT_THROW(drawRope(scene.rope(), drawer, 0), InvalidArgument);
}

}  // namespace
}  // namespace rope::bullet
