// SPDX-License-Identifier: MIT
#include "demos/scenes/resting_rope_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "rope/common/error.h"
#include "support/bad_settings.h"

namespace rope::demos {
namespace {

using Surface = RestingRopeSceneSettings::Surface;

std::string surfaceName(const ::testing::TestParamInfo<Surface>& info) {
  switch (info.param) {
    case Surface::kPlane: return "Plane";
    case Surface::kBox: return "Box";
    case Surface::kTriangleMesh: return "TriangleMesh";
  }
  return "Unknown";
}

class RestingRope : public ::testing::TestWithParam<Surface> {};

// A straight rope (default settings, 16 control points) laid on a flat surface stays coarse: it never
// has more control points than it started with, and once settled (after 0.5 s) no knot is inserted
// while it lies there for another second. It does lie there: still, one radius above the surface.
TEST_P(RestingRope, KeepsItsControlPointsAndInsertsNoKnotAtRest) {
  RestingRopeSceneSettings settings;
  settings.surface = GetParam();
  RestingRopeScene scene(settings);
  const int initial = scene.rope(0).rod().controlPointCount();
  ASSERT_EQ(initial, RodSettings{}.initialControlPoints);
  const int settle = static_cast<int>(std::lround(0.5 / scene.timeStep()));
  int most = initial, insertionsAtRest = 0, insertionsSettling = 0;
  for (int i = 0; i < 3 * settle; ++i) {
    const StepMeasurements m = scene.step();
    most = std::max(most, scene.maxControlPoints());
    (i < settle ? insertionsSettling : insertionsAtRest) += m.insertions;
  }
  const double radius = scene.rope(0).rod().settings().radius;
  RecordProperty("max_control_points", most);
  RecordProperty("final_control_points", scene.maxControlPoints());
  RecordProperty("insertions_settling", insertionsSettling);
  RecordProperty("insertions_at_rest", insertionsAtRest);
  RecordProperty("contacts", scene.rope(0).lastStep().contacts);
  EXPECT_LE(most, initial) << "refined to " << most << " control points (" << scene.maxControlPoints() << " at 1.5 s, "
                           << scene.rope(0).lastStep().contacts << " contacts)";
  EXPECT_EQ(insertionsAtRest, 0) << insertionsSettling << " insertions while settling";
  // The scenario itself: the rope lies still on the surface (measured on all three: 5e-15 to 7e-15
  // m/s, 0.44 um deep) at its coarsest, 4 control points with 8 contact samples (the README's figure).
  EXPECT_LT(scene.maxSpeed(), 1.0e-12);
  EXPECT_NEAR(scene.lowestPoint(), radius, 1.5e-6);
  EXPECT_EQ(scene.maxControlPoints(), 4);
  EXPECT_EQ(scene.rope(0).lastStep().contacts, 8);
  EXPECT_EQ(scene.rope(0).warnings().unsettledContactSteps, 0);  // its active set settles every substep
}

INSTANTIATE_TEST_SUITE_P(Surfaces, RestingRope, ::testing::Values(Surface::kPlane, Surface::kBox, Surface::kTriangleMesh),
                         surfaceName);

TEST(RestingRopeScene, LaysTheRopesSideBySideOnTheSurface) {
  RestingRopeSceneSettings settings;
  settings.ropeCount = 3;
  settings.surface = Surface::kTriangleMesh;
  RestingRopeScene scene(settings);
  ASSERT_EQ(scene.ropeCount(), 3);
  const double radius = RodSettings{}.radius;
  for (int i = 0; i < 3; ++i) {
    const Rod& rod = scene.rope(i).rod();
    EXPECT_NEAR(rod.length(), 1.0, 1e-9);
    EXPECT_NEAR(rod.position(rod.beginParameter()).y(), radius, 1e-12);
    if (i > 0) {
      EXPECT_NEAR(rod.position(0.0).z() - scene.rope(i - 1).rod().position(0.0).z(), settings.spacing, 1e-12);
    }
  }
  EXPECT_NEAR(scene.lowestPoint(), radius, 1e-12);
  EXPECT_EQ(scene.maxSpeed(), 0.0);
}

TEST(RestingRopeScene, RejectsBadSettingsNamingTheField) {
  using S = RestingRopeSceneSettings;
  test::expectEachRejected<S>({{"settings.ropeCount", [](S& s) { s.ropeCount = 0; }},
                               {"settings.spacing", [](S& s) { s.spacing = 0.005; }},
                               {"settings.gap", [](S& s) { s.gap = -0.001; }},
                               {"settings.ropeLength", [](S& s) { s.ropeLength = std::nan(""); }}},
                              [](const S& settings) { RestingRopeScene scene(settings); });
}

}  // namespace
}  // namespace rope::demos
