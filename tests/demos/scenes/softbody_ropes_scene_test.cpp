// SPDX-License-Identifier: MIT
#include "demos/scenes/softbody_ropes_scene.h"

#include <BulletSoftBody/btSoftBody.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "rope/common/error.h"
#include "rope/rod/rod_settings.h"
#include "support/bad_settings.h"

namespace rope::demos {
namespace {

// The benchmark's peer is a fair one: the soft ropes have the SplineRope ropes' node count, mass and
// radius, and lie still on the box (they neither sink through it nor bounce) after 0.5 s.
TEST(SoftBodyRopesScene, RopesMatchTheDefaultRopeAndLieStillOnTheBox) {
  SoftBodyRopesSceneSettings settings;
  settings.ropeCount = 3;
  SoftBodyRopesScene scene(settings);
  ASSERT_EQ(scene.ropeCount(), 3);
  EXPECT_DOUBLE_EQ(settings.linearDensity, RodSettings{}.effectiveLinearDensity());
  EXPECT_EQ(settings.radius, RodSettings{}.radius);
  double mass = 0.0;
  for (int k = 0; k < scene.rope(0).m_nodes.size(); ++k) mass += 1.0 / static_cast<double>(scene.rope(0).m_nodes[k].m_im);
  EXPECT_EQ(scene.rope(0).m_nodes.size(), 17);
  EXPECT_NEAR(mass, settings.linearDensity * settings.ropeLength, 1e-9);
  for (int i = 0; i < 120; ++i) scene.step();
  RecordProperty("lowest_node_mm", std::to_string(scene.lowestNode() * 1e3));
  EXPECT_GT(scene.lowestNode(), 0.0);
  EXPECT_LT(scene.lowestNode(), 2.0 * settings.radius);
  EXPECT_LT(scene.maxSpeed(), 1.0e-2);
}

TEST(SoftBodyRopesScene, RejectsBadSettingsNamingTheField) {
  using S = SoftBodyRopesSceneSettings;
  test::expectEachRejected<S>({{"settings.segments", [](S& s) { s.segments = 1; }},
                               {"settings.iterations", [](S& s) { s.iterations = 0; }},
                               {"settings.friction", [](S& s) { s.friction = 1.5; }},
                               {"settings.radius", [](S& s) { s.radius = std::nan(""); }}},
                              [](const S& settings) { SoftBodyRopesScene scene(settings); });
}

}  // namespace
}  // namespace rope::demos
