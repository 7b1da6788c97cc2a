// SPDX-License-Identifier: MIT
#pragma once
// Debug drawing of ropes through Bullet's btIDebugDraw (called by RopeWorld's action from
// btDiscreteDynamicsWorld::debugDrawWorld, or directly): the spline curve as a polyline, the
// collision capsules (when the drawer's mode has DBG_DrawWireframe) and the contacts of the last
// substep (DBG_DrawContactPoints; active contacts red, speculative ones yellow).

#include <LinearMath/btIDebugDraw.h>

#include "bullet_bridge/bullet_precision.h"

namespace rope::bullet {

class RopeObject;
class RopeWorld;

struct RopeDebugColours {
  btVector3 curve{0.1, 0.4, 1.0};
  btVector3 capsules{0.6, 0.6, 0.6};
  btVector3 activeContact{1.0, 0.1, 0.1};
  btVector3 speculativeContact{1.0, 0.9, 0.1};
};

// Draws one rope with `segmentsPerSpan` (>= 1) polyline pieces per knot span.
void drawRope(const RopeObject& rope, btIDebugDraw& drawer, int segmentsPerSpan = 8,
              const RopeDebugColours& colours = {});
void drawRopes(const RopeWorld& world, btIDebugDraw& drawer);

}  // namespace rope::bullet
