// SPDX-License-Identifier: MIT
#pragma once
// A scene's full dynamic state as a flat list of numbers, for the golden determinism hash
// (tests/reliability/golden_hash_test.cpp): any change that alters a trajectory changes some bit of
// it. Order is fixed (world object order, rope order), so the list is deterministic.

#include <vector>

#include "demos/scenes/physics_world.h"
#include "rope/rod/rod.h"
#include "rope/tractrix/tractrix_rope.h"

namespace rope::demos {

// Knots, control points, velocities, rest control points and pins (parameter and target).
void appendRodState(const Rod& rod, std::vector<double>& state);
// Knots and control points.
void appendTractrixState(const TractrixRope& rope, std::vector<double>& state);
// Every rigid body of the Bullet world in world order (transform, linear and angular velocity; rope
// capsules left out), then every rope of its RopeWorld in order (appendRodState). Kinematic ropes
// are the scene's to add (their capsules are left out here).
void appendWorldState(const PhysicsWorld& physics, std::vector<double>& state);

}  // namespace rope::demos
