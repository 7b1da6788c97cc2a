// SPDX-License-Identifier: MIT
#pragma once
// Planar leading-end paths for [B] §4's tractrix experiment ([B] does not give its path): a straight
// run, two arcs, then straight on, parametrised by arc length. Shared by the experiment test and
// the tractrix benchmark so that both measure the same thing.

#include "rope/common/types.h"

namespace rope::demos {

struct ArcPath {
  double headingStart = 0.0;  // rad, direction of the first straight run in the x-y plane
  double straight = 0.0;      // m, length of the first straight run
  double radius = 1.0;        // m, radius of both arcs
  double firstTurn = 0.0;     // rad, positive = left
  double secondTurn = 0.0;    // rad

  // The point at arc length s >= 0 from the origin (z = 0). Throws InvalidArgument("s", ...) for a
  // negative or non-finite s.
  Vec3 at(double s) const;
};

// 1 m pull along the rope, then left 90° and right 180° on 1.2 m radii.
ArcPath sBendPath();
// Much harder: pulled sideways, then a 270° loop and a 180° counter-turn on 1.5 m radii.
ArcPath loopPath();

}  // namespace rope::demos
