// SPDX-License-Identifier: MIT
#pragma once
// What a user configures for a rope living in a Bullet world: the contact laws (rope-body: a penalty
// line load with damping and Coulomb friction with sticking; rope-rope: penalty point contacts at
// crossings and in self-contact, a distributed load where two ropes touch along a stretch), the
// collision proxies and the broadphase filter. SI units.
// The rope's material, gravity and discretisation stay in rope::RodSettings.

#include <LinearMath/btScalar.h>
#include <LinearMath/btVector3.h>

#include "bullet_bridge/bullet_precision.h"

namespace rope::bullet {

struct BulletRopeSettings {
  // ---- rope-body contact: a pressure along the touching stretch of the curve (contact/line_contact.h) ----
  // The rope presses on a body with a line load p = k (-gap) - c (normal approach speed) per metre of
  // rope, integrated along every touching stretch by Gauss-Legendre quadrature into the consistent
  // generalised force sum_q w_q b_i(s_q) p(s_q) and its stiffness into the rope's implicit step
  // (Rod::addSpringSample). A penetration of gap metres over the whole rope holds k * gap newtons per
  // metre: a 5 mm nylon rope (0.09 kg/m) rests about 0.45 um deep on a floor.
  //
  // Penalty stiffness, N/m per m of rope (N/m^2), > 0. The rope side is implicit and stable for any
  // value; on a dynamic body the forces are explicit impulses, so the sum of the stiffness of all the
  // samples on one body is capped at bodyStabilityFactor * m_eff / h^2 (m_eff: the body's smallest
  // effective mass at the contact points). Not much stiffer by default: the resting depth must stay
  // well above btScalar round-off of the contact distance in float builds (about 1e-7 m at 1 m).
  double lineContactStiffness = 2.0e6;
  // Penalty damping along the normal, N s/m per m of rope (N s/m^2), >= 0 (capped on light bodies like
  // the stiffness, at bodyStabilityFactor * m_eff / h). About critical for the default stiffness and a
  // 5 mm nylon rope (2 sqrt(k m') = 850 N s/m^2); backward Euler damps the rest. Much more turns a
  // resting rope's jitter into normal forces larger than its weight, which pull and release contacts.
  double lineContactDamping = 1.0e3;
  // A speculative sample (still apart, but closing within the step at the current approach speed)
  // acts as a damper of this coefficient towards the approach speed that exactly closes the gap,
  // -gap/h, so that a fast rope ends the step on the surface instead of being merely slowed by the
  // spring (a soft law let a 17 m/s rope pass a 1 cm plate). N s/m per m of rope, >= 0; it must be
  // large against the rope's mass per metre over h (about 90 N s/m^2 for a 1 cm rope at 1/240 s).
  double lineSpeculativeDamping = 2.0e5;
  // Gauss-Legendre points per touching stretch of one capsule, in [1, 8]. Two integrate the cubic
  // basis times a linear pressure exactly on each capsule piece (a quarter of a knot span by default).
  int contactQuadraturePoints = 2;
  // A touching stretch shorter than this share of the knot span around it is a concentrated load
  // (a thin bar, an edge the rope crosses, a pulley's rim seen from far away): it gets a knot at its
  // centre so that the curve can kink there, and keeps it while the load lasts. In (0, 1].
  double concentratedContactRatio = 0.5;

  // The rope's own Coulomb friction coefficient, >= 0 (0 = frictionless). Combined the Bullet way
  // (friction_combination.h): against a body, friction * body.getFriction() (clamped to 10), so the
  // default 1 gives 0.5 against a default Bullet body (friction 0.5) and a body's setFriction
  // changes it; against another rope, the product of the two ropes' coefficients (1 by default).
  // RopeWorld::setBodyFrictionCombiner / setRopeFrictionCombiner replace the rule.
  // Rope-body samples stick (each one held by a tangential spring of lineContactStiffness and
  // lineContactDamping to where it began to stick, carried along the curve as knots come and go)
  // until that spring would need more than friction * normal force, then slide with exactly that
  // force against the sliding direction.
  double friction = 1.0;
  // Friction speed scale, m/s, > 0. Rope-body and distributed rope-rope samples: a sliding sample
  // slower than this sticks again at the next substep. Rope-rope point contacts: below it the friction
  // force grows linearly with the sliding speed (viscous "sticking"), above it it is mu * f_n against
  // the sliding direction.
  double frictionVelocity = 1.0e-3;

  // ---- gravity ----
  // Where the rope's gravity comes from. kWorld: every substep the rope takes gravityScale times its
  // Bullet world's getGravity(), like a rigid body (set the world's gravity and the ropes follow;
  // the rod's RodSettings::gravity is overwritten). kRod: the rod's own RodSettings::gravity (change
  // it with Rod::setGravity), e.g. a weightless rope in a world with gravity.
  enum class GravitySource { kWorld, kRod };
  GravitySource gravitySource = GravitySource::kWorld;
  double gravityScale = 1.0;  // finite, any sign; used with kWorld

  // ---- aerodynamic drag (contact/distributed_loads.cpp; docs/method.md §15) ----
  // A quadratic (Morison) drag per metre of rope against the fluid moving at windVelocity: with w the
  // rope's velocity relative to the fluid, split into the parts normal (w_n) and along (w_t) the
  // rope, q = -(1/2) rho d (C_n |w_n| w_n + pi C_t |w_t| w_t) newtons per metre (d = 2 radius: C_n on
  // the projected area, C_t on the wetted area), integrated along the rope by Gauss-Legendre and
  // treated implicitly (its velocity Jacobian enters the rope's step), so it is stable at any speed.
  // Fluid density, kg/m^3, >= 0; 0 (the default) turns drag off. Air 1.2, water 1000.
  double fluidDensity = 0.0;
  // Cross-flow drag coefficient of the rope's cylinder, >= 0 (about 1.2 for a smooth cylinder at
  // Reynolds numbers 1e3-1e5).
  double normalDragCoefficient = 1.2;
  // Skin-friction coefficient along the rope, >= 0 (about 0.01 for a rope in axial flow).
  double tangentialDragCoefficient = 0.01;
  // Velocity of the fluid, m/s, world frame, finite (wind, a current).
  btVector3 windVelocity{0, 0, 0};

  // ---- rope-rope and self-contact (contact/rope_rope_contact.h) ----
  // Penalty stiffness of one contact point, N/m, > 0; its damping along the normal, N s/m, >= 0; and
  // the speculative damper of a closing contact, N s/m, >= 0 (see lineSpeculativeDamping). Two ropes
  // use the smaller value of each of the two ropes'. Where two ropes touch along a stretch (one wrapped
  // round or lying along the other) the contact is distributed: each of these per contact spacing
  // (the sum of the radii) of rope, sampled by contactQuadraturePoints per capsule, with friction that
  // sticks like rope-body samples'.
  double contactStiffness = 1.0e4;
  double contactDamping = 50.0;
  double speculativeDamping = 1.0e3;

  // ---- collision proxies ----
  // Capsules per knot span, in [1, 16]: the collision geometry is the chain of capsules over
  // capsulesPerSpan equal parameter pieces of every non-empty span; rebuilt after each step. The cost
  // grows faster than the count, since every capsule's box (padded by the margins) overlaps more of
  // its shorter neighbours in the broadphase: a 64-point rope resting on a box took 3.5 / 27 / 307 ms
  // per 1/240 s step at 4 / 16 / 64 (measured in one run), so the range stops at 16 (was 64).
  int capsulesPerSpan = 4;
  // Speculative contact distance, m, >= 0: contacts are found up to this gap before touching and act
  // only if the step is predicted to close them. Added to every swept bounding box.
  double speculativeMargin = 0.01;
  // Time the swept boxes of a freshly added rope cover before the first step told the real step, s, > 0.
  double initialPredictionTime = 1.0 / 60.0;
  // Share of the stable explicit limit used on dynamic bodies, in (0, 1] (see lineContactStiffness).
  double bodyStabilityFactor = 0.25;
  // Broadphase filter of the rope's collision object. The default group is a bit no stock Bullet filter uses;
  // the mask accepts everything, rope capsules included, so that ropes meet each other (and
  // themselves) through the same broadphase. Two ropes touch only if each one's mask accepts the
  // other's group; clearing the group bit from a rope's mask turns its rope-rope and self-contact off.
  int collisionGroup = 1 << 10;
  int collisionMask = -1;

  // ---- rope-rope and self-contact (contact/rope_rope_contact.h) ----
  // Whether the rope collides with itself. Rope-rope contact between two ropes is governed by the
  // broadphase filter above. The contact law is contactStiffness, contactDamping, speculativeDamping,
  // friction and frictionVelocity above.
  bool selfContact = true;
  // Two points of the same rope closer than this along the rest curve never count as touching, m of
  // rest length, >= 0; kDerivedExclusion: 4 rope radii. Points within pi r of each other along a
  // bent rope can be closer than one diameter without any overlap (a U-turn of bending radius r),
  // so the exclusion must exceed pi r; it depends on the material, not on where the knots are.
  static constexpr double kDerivedExclusion = -1.0;
  double selfContactExclusion = kDerivedExclusion;
  // The exclusion length for a rope of this radius (m).
  double effectiveSelfContactExclusion(double radius) const {
    return selfContactExclusion >= 0.0 ? selfContactExclusion : 4.0 * radius;
  }

  // Throws rope::InvalidArgument naming the field ("settings.contactStiffness", ...) and its value for
  // anything outside the ranges above, NaN and infinity included.
  void validate() const;
};

}  // namespace rope::bullet
