// SPDX-License-Identifier: MIT
// Exact segment-capsule entry (narrowphase/ray_capsule.h) against hand-solved cases.
#include "bullet_bridge/narrowphase/ray_capsule.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rope::bullet {
namespace {

// Axis from (0, 0, 0) to (1, 0, 0), radius 0.1.
Capsule unitCapsule() {
  Capsule capsule;
  capsule.a = btVector3(0, 0, 0);
  capsule.b = btVector3(1, 0, 0);
  capsule.radius = btScalar(0.1);
  return capsule;
}

TEST(RayCapsule, EntersTheCylinderWhereTheQuadraticSays) {
  // Down from y = 1 at x = 0.3, z = 0.06: enters at y = sqrt(0.1^2 - 0.06^2) = 0.08.
  double lambda = 0.0, t = 0.0;
  ASSERT_TRUE(rayCapsule(btVector3(0.3, 1, 0.06), btVector3(0, -2, 0), unitCapsule(), lambda, t));
  EXPECT_NEAR(lambda, (1.0 - 0.08) / 2.0, 1e-15);
  EXPECT_NEAR(t, 0.3, 1e-15);
}

TEST(RayCapsule, EntersAnEndSphereBeyondTheAxis) {
  // Along the axis from x = -1: meets the sphere round a at x = -0.1, t = 0.
  double lambda = 0.0, t = 1.0;
  ASSERT_TRUE(rayCapsule(btVector3(-1, 0, 0), btVector3(4, 0, 0), unitCapsule(), lambda, t));
  EXPECT_NEAR(lambda, 0.9 / 4.0, 1e-15);
  EXPECT_EQ(t, 0.0);
  // Obliquely past the far end: x = 1.05, y from 1 down meets the sphere round b at y = sqrt(0.0075).
  ASSERT_TRUE(rayCapsule(btVector3(1.05, 1, 0), btVector3(0, -1, 0), unitCapsule(), lambda, t));
  EXPECT_NEAR(lambda, 1.0 - std::sqrt(0.0075), 1e-15);
  EXPECT_EQ(t, 1.0);
}

TEST(RayCapsule, MissesStopsShortAndNeverEntersFromInside) {
  double lambda = 0.0, t = 0.0;
  EXPECT_FALSE(rayCapsule(btVector3(0.5, 1, 0.2), btVector3(0, -2, 0), unitCapsule(), lambda, t));   // beside it
  EXPECT_FALSE(rayCapsule(btVector3(0.5, 1, 0), btVector3(0, -0.5, 0), unitCapsule(), lambda, t));   // ends above it
  EXPECT_FALSE(rayCapsule(btVector3(0.5, 0.05, 0), btVector3(0, 1, 0), unitCapsule(), lambda, t));  // starts inside
  EXPECT_FALSE(rayCapsule(btVector3(0.5, 1, 0), btVector3(0, 0, 0), unitCapsule(), lambda, t));     // no segment
}

}  // namespace
}  // namespace rope::bullet
