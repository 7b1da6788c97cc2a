#pragma once
// What a user configures for a rope living in a Bullet world: the contact law (penalty with damping
// plus regularised Coulomb friction), the collision proxies and the broadphase filter. SI units.
// The rope's material, gravity and discretisation stay in rope::RodSettings.

#include <LinearMath/btScalar.h>

#include "bullet_bridge/bullet_precision.h"

namespace rope::bullet {

struct BulletRopeSettings {
  // Penalty stiffness of one contact point, N/m, > 0. Enters the rope's implicit system
  // (Rod::addSpring), so the rope side is stable for any value; on a dynamic body the force is an
  // explicit impulse, so per contact it is capped at bodyStabilityFactor * m_eff / h^2 (m_eff the
  // body's effective mass at the contact point along the normal). Not much stiffer by default: the
  // resting depth per contact (force / k, often < 1e-6 m) must stay well above btScalar round-off of
  // the contact distance, or float builds see noisy normal forces (measured: at 5e4 a rope on a float
  // ramp chattered and its friction doubled; at 1e4 both precisions match Coulomb within 2%).
  double contactStiffness = 1.0e4;
  // Penalty damping along the normal, N s/m, >= 0 (capped like the stiffness, by factor * m_eff / h).
  double contactDamping = 50.0;
  // A speculative contact (still apart, but closing within the step at the current approach speed)
  // acts as a damper of this coefficient towards the approach speed that exactly closes the gap,
  // -gap/h, so that a fast rope ends the step on the surface instead of being merely slowed by the
  // spring (which let a 17 m/s rope pass a 1 cm plate). N s/m, >= 0; it must be large against the
  // rope's local mass over h (about 1 N s/m for a 1 cm rope at 1/240 s). Capped on light bodies
  // like contactDamping.
  double speculativeDamping = 1.0e3;
  // Coulomb friction coefficient, >= 0 (0 = frictionless).
  double friction = 0.5;
  // Regularisation velocity of Coulomb friction, m/s, > 0: below it the friction force grows linearly
  // with the sliding speed (viscous "sticking"), above it it is mu * f_n against the sliding direction.
  double frictionVelocity = 1.0e-3;
  // Capsules per knot span, in [1, 64]: the collision geometry is the chain of capsules over
  // capsulesPerSpan equal parameter pieces of every non-empty span; rebuilt after each step.
  int capsulesPerSpan = 4;
  // Knots at contacts ([A] §4), m of rope parameter, >= 0: a contact acts at its own parameter s (and
  // so gets a knot there, giving the rope local freedom to wrap around an edge) only when no knot lies
  // within this distance of s; otherwise it is shared between the two knots around s by the lever
  // rule (same total force, no new knot). Larger values keep a rope lying along a surface from
  // refining (it tends to spans of a few times this value, up to RodSettings::maxControlPoints), but
  // the lever rule is not the consistent load b_i(s) f: above ~1 cm it let resting contact become
  // uneven enough to upset friction (measured on the ramp test), hence the small default.
  double contactKnotSpacing = 0.005;
  // Speculative contact distance, m, >= 0: contacts are found up to this gap before touching and act
  // only if the step is predicted to close them. Added to every swept bounding box.
  double speculativeMargin = 0.01;
  // Time the swept boxes of a freshly added rope cover before the first step told the real step, s, > 0.
  double initialPredictionTime = 1.0 / 60.0;
  // Share of the stable explicit limit used on dynamic bodies, in (0, 1] (see contactStiffness).
  double bodyStabilityFactor = 0.25;
  // Broadphase filter of the rope's capsules. The default group is a bit no stock Bullet filter uses;
  // the mask accepts everything, rope capsules included, so that ropes meet each other (and
  // themselves) through the same broadphase. Two ropes touch only if each one's mask accepts the
  // other's group; clearing the group bit from a rope's mask turns its rope-rope contact off.
  int collisionGroup = 1 << 10;
  int collisionMask = -1;

  // ---- rope-rope and self-contact (rope_rope_contact.h) ----
  // Whether the rope collides with itself. Rope-rope contact between two ropes is governed by the
  // broadphase filter above. The contact law is contactStiffness, contactDamping, speculativeDamping,
  // friction and frictionVelocity (for two ropes, the smaller value of each of the two ropes').
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
