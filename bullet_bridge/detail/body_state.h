// SPDX-License-Identifier: MIT
#pragma once
// Whether a Bullet body's state is usable by the ropes this substep. A user's body can end up with a
// NaN velocity or transform (an explosion elsewhere in the scene, a bad setLinearVelocity); a rope
// that read it would put NaN into its own step and hand NaN impulses back. Such a body is passed
// over for the substep and counted (RopeStepRecord::skippedBodies,
// KinematicRopeStepReport::unsupportedBodies) instead.

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include "bullet_bridge/bullet_precision.h"
#include "rope/common/types.h"

namespace rope::bullet {

// Transform, linear and angular velocity, inverse mass, inverse inertia and the accumulated force
// and torque all finite.
bool bodyStateFinite(const btRigidBody& body);

// The body as a dynamic rigid body that takes impulses, or nullptr for static and kinematic objects
// and for collision objects that are not rigid bodies.
btRigidBody* dynamicBody(const btCollisionObject& object);

// Velocity of the body's material point at `point` (world frame), m/s; for a kinematic rope's object,
// its surface's at `point` near capsule childIndex (Contact::childIndex); zero for any other
// collision object that is not a rigid body.
Vec3 pointVelocity(const btCollisionObject& object, const btVector3& point, int childIndex);

// Acceleration of a dynamic body's material point at `arm` from its centre of mass (world frame) that
// the forces and torques applied to the body for this step give it, m/s^2: a = F/m + (I^-1 tau) x r,
// with F and tau Bullet's accumulated totals (the world's gravity, applied at the start of
// stepSimulation, and the user's applyForce/applyTorque). The body integrates them in its next step
// whatever the rope does; an attachment that predicts the body point without them mistakes the
// hanging load's fall under gravity, which the rope's own impulse cancels, for stretch.
Vec3 pointAccelerationFromForces(const btRigidBody& body, const btVector3& arm);

// How far any point of the object's surface can move in h seconds at its current velocity, m: h (|v| +
// |omega| e), e half the diagonal of its broadphase box. 0 for an object that is not a rigid body or
// has no broadphase handle; not finite for a body with a non-finite velocity.
double sweptReach(const btCollisionObject& object, double h);

// The inverse-mass matrix of a dynamic body's material point at `arm` from its centre of mass (world
// frame), m/(N s^2): an impulse J there changes the point's velocity by W J, W = I/m - [r]x I^-1 [r]x
// (symmetric positive semidefinite; symmetrised against the round-off of Bullet's world inertia).
Eigen::Matrix3d pointInverseMass(const btRigidBody& body, const btVector3& arm);

}  // namespace rope::bullet
