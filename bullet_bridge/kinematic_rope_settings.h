// SPDX-License-Identifier: MIT
#pragma once
// What a user configures for a kinematic (tractrix) rope in a Bullet world (kinematic_rope.h): its
// collision geometry, how it pushes dynamic bodies, and its broadphase filter. SI units. The rope's
// own kinematics (variant, thresholds, segment count) stay in rope::TractrixSettings.
//
// The rope is kinematic: it moves only by its leading end and nothing pushes it back. A dynamic
// body it overlaps gets a one-way contact impulse (contact/kinematic_push.h) that gives the body, at the
// contact point, at least the rope's normal velocity there, plus a separating speed proportional
// to the penetration; the impulse is the body's own effective mass times a velocity change, so it
// is stable for any body mass (a penalty spring on an explicit body would need a stiffness cap).
// All contacts of one body are solved together like Bullet's solver does (solverIterations).

namespace rope::bullet {

struct KinematicRopeSettings {
  // Largest radius and speculativeMargin, m. Every capsule's broadphase box is padded by both, and
  // Bullet takes an object whose box diagonal reaches 1e6 m out of the simulation
  // (btCollisionWorld::updateSingleAabb); larger values also overflowed the contact arithmetic
  // (a radius of 1e308 put NaN into the bodies it pushed).
  static constexpr double kMaxSize = 1.0e5;
  // Radius of the rope's capsules, m, in (0, kMaxSize].
  double radius = 0.01;
  // Capsules per knot span of the spline variants, in [1, 64]: the collision geometry is the chain of
  // capsules over capsulesPerSpan equal parameter pieces of every non-empty span. The polyline
  // variant (TRX, degree 1) always uses one capsule per segment, which is exact.
  int capsulesPerSpan = 4;
  // Speculative contact distance, m, in [0, kMaxSize]: contacts are found up to this gap before the
  // surfaces touch, and a body that is still apart is pushed only as much as needed so that the rope
  // does not pass the gap within the next substep at its current speed (no tunnelling through thin
  // bodies). Also pads every broadphase box.
  double speculativeMargin = 0.01;
  // Fraction of a penetration removed per substep, in (0, 1]: the pushed body leaves the rope at
  // least at penetrationRecovery * depth / h relative to it (Baumgarte-like). 1 removes a
  // penetration in one substep (harsh), small values let bodies sink visibly.
  double penetrationRecovery = 0.2;
  // Coulomb friction coefficient between rope and body, finite and >= 0: the tangential impulse
  // drags the body's contact point towards the rope's tangential velocity, at most friction times
  // the normal impulse of the same contact.
  double friction = 0.3;
  // Projected Gauss-Seidel sweeps over the contacts of one body per substep, in [1, 1000]. With one
  // sweep the first contact takes the whole load and a body resting on several contacts creeps and
  // turns (measured: a box on a rope's two legs drifted 17 mm in 2 s with 1 sweep, 3 um with 10).
  int solverIterations = 10;
  // Broadphase filter of the rope's capsules. The default group is a bit that neither stock Bullet
  // filters nor the dynamic ropes' default group (1 << 10) use; the mask accepts everything. A body
  // is pushed only if each side's mask accepts the other's group.
  int collisionGroup = 1 << 11;
  int collisionMask = -1;

  // Throws rope::InvalidArgument naming the field ("settings.radius", ...) and its value for
  // anything outside the ranges above, NaN and infinity included.
  void validate() const;
};

}  // namespace rope::bullet
