#pragma once
// Whether a Bullet body's state is usable by the ropes this substep. A user's body can end up with a
// NaN velocity or transform (an explosion elsewhere in the scene, a bad setLinearVelocity); a rope
// that read it would put NaN into its own step and hand NaN impulses back. Such a body is passed
// over for the substep and counted (RopeStepRecord::skippedBodies,
// KinematicRopeStepReport::unsupportedBodies) instead.

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include "bullet_bridge/bullet_precision.h"

namespace rope::bullet {

// Transform, linear and angular velocity, inverse mass and inverse inertia all finite.
bool bodyStateFinite(const btRigidBody& body);

}  // namespace rope::bullet
