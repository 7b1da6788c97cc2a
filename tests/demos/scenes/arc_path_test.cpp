// SPDX-License-Identifier: MIT
#include "demos/scenes/arc_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "rope/common/error.h"

namespace rope::demos {
namespace {

// The path is parametrised by arc length: points 1 mm apart along it are 1 mm apart in space (to
// second order), across the straight runs and both arcs.
TEST(ArcPath, IsParametrisedByArcLength) {
  for (const ArcPath& path : {sBendPath(), loopPath()}) {
    for (double s = 0.0; s < 20.0; s += 0.25) {
      EXPECT_NEAR((path.at(s + 1e-3) - path.at(s)).norm(), 1e-3, 1e-7) << s;
    }
  }
  // The S-bend starts with a 1 m straight pull along +x.
  EXPECT_NEAR((sBendPath().at(1.0) - Vec3(1, 0, 0)).norm(), 0.0, 1e-12);
}

TEST(ArcPath, RejectsNegativeOrNonFiniteArcLength) {
  EXPECT_THROW(sBendPath().at(-1.0), InvalidArgument);
  EXPECT_THROW(sBendPath().at(std::numeric_limits<double>::quiet_NaN()), InvalidArgument);
}

}  // namespace
}  // namespace rope::demos
