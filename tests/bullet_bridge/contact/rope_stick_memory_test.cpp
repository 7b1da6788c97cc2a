// SPDX-License-Identifier: MIT
#include "bullet_bridge/contact/rope_stick_memory.h"

#include <gtest/gtest.h>

#include "bullet_bridge/rope_object.h"
#include "demos/scenes/knot_scene.h"

namespace rope::bullet {
namespace {

// Two ropes whose addresses name the entries (the memory never reads them).
struct TwoRopes {
  RopeObject a{Rod::fromSegment(demos::KnotSceneSettings::defaultRod(), Vec3(0, 0, 0), Vec3(1, 0, 0)),
               demos::KnotSceneSettings::defaultBridge()};
  RopeObject b{Rod::fromSegment(demos::KnotSceneSettings::defaultRod(), Vec3(0, 1, 0), Vec3(1, 1, 0)),
               demos::KnotSceneSettings::defaultBridge()};
};

TEST(RopeStickMemory, InterpolatesBetweenNeighboursAndCopiesALoneOne) {
  TwoRopes ropes;
  RopeStickMemory memory;
  memory.add(ropes.a, ropes.b, 0.20, Vec3(1e-4, 0, 0), false);
  memory.add(ropes.a, ropes.b, 0.10, Vec3(0, 2e-4, 0), true);  // any order
  memory.add(ropes.b, ropes.a, 0.15, Vec3(0, 0, 5e-4), false);  // the other way round: its own field
  Vec3 stretch(9, 9, 9);
  bool sliding = false;
  EXPECT_FALSE(memory.find(ropes.a, ropes.b, 0.15, 0.1, stretch, sliding));  // not committed yet
  memory.commit();
  ASSERT_TRUE(memory.find(ropes.a, ropes.b, 0.125, 0.1, stretch, sliding));
  // A quarter of the way from 0.10 to 0.20: exact linear interpolation, flag of the nearer one.
  EXPECT_NEAR((stretch - Vec3(0.25e-4, 1.5e-4, 0)).norm(), 0.0, 1e-18);
  EXPECT_TRUE(sliding);
  ASSERT_TRUE(memory.find(ropes.a, ropes.b, 0.25, 0.1, stretch, sliding));  // beyond the last: copied
  EXPECT_EQ(stretch, Vec3(1e-4, 0, 0));
  EXPECT_FALSE(sliding);
  EXPECT_FALSE(memory.find(ropes.a, ropes.b, 0.5, 0.1, stretch, sliding));  // out of reach
  ASSERT_TRUE(memory.find(ropes.b, ropes.a, 0.15, 0.01, stretch, sliding));
  EXPECT_EQ(stretch, Vec3(0, 0, 5e-4));
  EXPECT_EQ(memory.size(), 3);
}

TEST(RopeStickMemory, ForgettingARopeDropsEveryEntryNamingIt) {
  TwoRopes ropes;
  RopeObject third{Rod::fromSegment(demos::KnotSceneSettings::defaultRod(), Vec3(0, 2, 0), Vec3(1, 2, 0)),
                   demos::KnotSceneSettings::defaultBridge()};
  RopeStickMemory memory;
  memory.add(ropes.a, ropes.b, 0.1, Vec3(1e-4, 0, 0), false);
  memory.add(ropes.b, ropes.a, 0.1, Vec3(1e-4, 0, 0), false);
  memory.add(ropes.a, third, 0.1, Vec3(1e-4, 0, 0), false);
  memory.commit();
  memory.forget(ropes.b);
  EXPECT_EQ(memory.size(), 1);
  Vec3 stretch;
  bool sliding = false;
  EXPECT_TRUE(memory.find(ropes.a, third, 0.1, 0.01, stretch, sliding));
  EXPECT_FALSE(memory.find(ropes.a, ropes.b, 0.1, 0.01, stretch, sliding));
  memory.clear();
  EXPECT_EQ(memory.size(), 0);
  // A commit after nothing was added empties the store: the stick state lasts one substep unless renewed.
  memory.add(ropes.a, third, 0.1, Vec3(1e-4, 0, 0), false);
  memory.commit();
  memory.commit();
  EXPECT_EQ(memory.size(), 0);
}

}  // namespace
}  // namespace rope::bullet
