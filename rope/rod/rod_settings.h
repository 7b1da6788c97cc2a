// SPDX-License-Identifier: MIT
#pragma once
// What a user configures for a dynamic rod ([A] §3.2–4; docs/method.md §5–§10): material, discretisation and
// adaptivity. SI units throughout. The rod copies the settings at creation; what a step changes
// (control points, velocities, knots, pins) lives in the Rod itself.

#include "rope/common/types.h"

namespace rope {

// How the stretching integral (docs/method.md §6–§7) is sampled per knot span.
enum class StretchingQuadrature {
  // Exact Gauss–Legendre (2d-1 points per span): B_im and B_impq exactly as in method eq. 15, the energy
  // exactly additive and refinement-invariant. Like every exactly integrated displacement-based rod it
  // suffers membrane locking: ~2d-1 length conditions per span against about one control point's worth
  // of freedom per span, so a stiff rope (EA >> its weight) cannot bend into its equilibrium with few
  // control points (measured: a 78.5 kN rope, slack ratio 1.25, 11-16 control points hangs 9-10 % too
  // deep and stays V-shaped; from a straight start it hardly sags at all).
  kExact,
  // Reduced rule: one point per interior span and d-1 extra points shared by the two end spans, i.e.
  // n-1 strain samples — the dimension of the spline space C' lives in (degree d-1) — so the strain is
  // controlled without over-constraining (same catenary: 0.02 % sag error). The n-1 weights are solved
  // for (a banded system, O(n) per knot change) so that the rule integrates that whole space exactly:
  // a uniform strain is then exact on any knots (patch test). Costs: the energy of a given curve
  // changes slightly under refinement (quadrature error), and a strain that varies inside a span around
  // the sampled value has no stretching energy, so in very short spans (below ~the rope diameter) a
  // curve can fold back inside a span held only by bending; minKnotSpacing keeps adaptivity out of
  // that range.
  kLockingFree,
};

// How the rod's step integrates in time (docs/method.md §8). Both are linearised once about the start of
// the step and solve one block-banded system per step, O(n); both hold pins and clamps exactly at the end
// of the step, keep q_new = q + h v_new, and apply loads, springs (contacts, attachments), gravity and
// mass damping with the full step h, so the momentum a step gives the rope is exactly what the loads
// deliver (the Bullet bridge's two-way exchange depends on it). They differ only in how the rod's own
// internal forces (stretching, bending, stiffness damping) are weighted.
enum class TimeIntegrator {
  // The two-step backward differentiation formula, BDF2 (C. W. Gear, "Numerical Initial Value Problems in
  // Ordinary Differential Equations", Prentice-Hall 1971; linearised once per step as in K.-J. Choi and
  // H.-S. Ko, "Stable but responsive cloth", ACM Transactions on Graphics 21(3), 2002, 604–611), applied
  // to the internal forces (method eqs. 22a–22c): second order, L-stable. It damps a mode of frequency
  // omega by O((omega h)^4) per step where omega h << 1 and kills the stiff ones (omega h >> 1) within a
  // step or two: a 1 m pendulum keeps over 99.9 % of its swing in 20 s even at h = 1/60 s. Its one step
  // of history restarts (one backward-Euler step) when h changes, knots change, the rod is cut or its
  // state is replaced.
  kBdf2,
  // Backward Euler linearised once ([A]'s "fast implicit Euler"; Baraff & Witkin 1998), method eq. 22:
  // first order, L-stable. Damps a mode by about (omega h)^2 / 2 per step: a 1 m pendulum loses 31 % of
  // its swing in 20 s at h = 1/240 s and 77 % at 1/60 s. For comparison with [A] and for users who want
  // that damping.
  kBackwardEuler,
};

// Which test a knot removal must pass (docs/method.md §10).
enum class RemovalCriterion {
  // [A]/[B]: the control polygon is straight around the knot (removeAngle) and the curve, the rest
  // curve and the velocity field move by at most the absolute bounds. A small vibration moves
  // nothing by much, so it is coarsened away (measured from 16 control points: the third mode of a
  // taut string 22 % low at 5-8 points, of a rope hanging from one end 29 % high at 5-6; tip-loaded
  // cantilevers up to 1.0e-3 L off the elastica at 6-10 points, against 4e-5 L at 16).
  kPolygon,
  // kPolygon, and the coarser spline must represent the state's mechanics over the spans the
  // removal changes (rope/rod/adaptivity.h, docs/method.md §10): the velocity field (in the mass norm
  // and in its curvature) and the internal energy (bending, and the tension's geometric stiffness)
  // may each change by at most removalRelativeError of their own size there. A straight, still or
  // rigidly moving rope is coarsened as before; a vibrating or loaded one keeps the knots its motion
  // and its internal forces need (measured: modes and cantilevers as at fixed resolution).
  // Measured as the only test, ropes in contact kept the knots inserted at their contacts (a resting
  // rope 24 control points instead of at most 16), a dropped pile drifted 7.5e-4 (its test allows
  // 5e-4), a rope on a capstan crept at 3.3e-4 m/s (3e-7 allowed) and the knot scene removed no
  // knot: contact jitter is far above its floors (docs/method.md §10).
  kMechanical,
  // The default: kMechanical, except after a step in contact (Rod::markContact; the Bullet bridge
  // marks a substep with body contact candidates, or after one with rope-rope contact), which is
  // judged by kPolygon. A free, pinned, attached or force-loaded rope keeps the knots its modes and
  // its load need; a rope in contact is coarsened by its shape, as the contact pressure, not the
  // rope's own modes, sets its motion there.
  kMechanicalOutOfContact,
};

struct RodSettings {
  // Sentinel values: derive the quantity from the others (see effective*() below).
  static constexpr double kDerived = -1.0;

  // ---- material ----
  double restLength = 1.0;         // m, > 0. Rest length of ropes created from a segment, and the
                                   // length a polyline/control-point rest shape is scaled to.
  double radius = 0.005;           // m, > 0. Cross-section area A = pi r^2.
  double linearDensity = kDerived; // kg/m of rest length, > 0, or kDerived: materialDensity * A.
  double materialDensity = 1150.0; // kg/m^3, > 0 (nylon). Used when linearDensity == kDerived.
  double youngsModulus = 1.0e9;    // Pa, > 0. Stretching stiffness EA = youngsModulus * A.
  double bendingStiffness = kDerived;  // N m^2, >= 0, or kDerived: EI = youngsModulus * pi r^4 / 4.
                                       // 0 reproduces [A], which had stretching only.
  // Damping D = massDamping * M + stiffnessDamping * K + materialDamping * K_m (docs/method.md eq. 20),
  // all >= 0. K is the stiffness of stretching and bending, K_m the same without its tension term.
  //  - massDamping: a drag on every motion, rigid motion included (a rope in still air has next to none).
  //  - stiffnessDamping: Rayleigh damping on the whole stiffness. Its tension term also damps a taut
  //    rope's swing and transverse vibration; use it to settle a scene quickly.
  //  - materialDamping: the material's own (Kelvin–Voigt) damping: it resists strain rates (stretching
  //    and bending) and not rigid motion or a swing. A mode of angular frequency w is damped at the
  //    ratio w * materialDamping / 2 of critical (loss factor w * materialDamping). The default, 1 ms,
  //    damps a 10 kg box bouncing on 1 m of the crane scene's 4 mm rope (w about 50 rad/s) at 2.5 %
  //    of critical (loss factor 0.05, the order of a nylon rope's) and leaves a swing alone, while the
  //    stiff modes a discretised rope carries and no rope shows (kHz and above) are overdamped. It is
  //    what keeps a knot pulled tight from overshooting its pull. 0: the undamped model.
  double massDamping = 0.0;         // 1/s
  double stiffnessDamping = 0.0;    // s
  double materialDamping = 1.0e-3;  // s
  Vec3 gravity = Vec3(0.0, -9.81, 0.0);  // m/s^2, finite (y up, as in Bullet's demos)

  // ---- time integration (docs/method.md §8) ----
  TimeIntegrator timeIntegrator = TimeIntegrator::kBdf2;

  // ---- discretisation ----
  int degree = 3;                  // 1..kMaxDegree (cubic as in [A]); bending needs degree >= 2.
  int initialControlPoints = 16;   // ropes created from a segment; in [minControlPoints, maxControlPoints]
  StretchingQuadrature stretchingQuadrature = StretchingQuadrature::kLockingFree;

  // ---- adaptivity ([A] §4; docs/method.md §10) ----
  bool adaptive = true;            // false: the knot vector only changes on explicit request
  int minControlPoints = 4;        // >= degree + 1
  int maxControlPoints = 128;      // in [minControlPoints, kMaxControlPointsLimit]
  // Largest allowed maxControlPoints: 2^16 points is a 65 m rope at 1 mm spacing, tens of MB of step
  // matrix; far beyond it a count only allocates (2^30 asked for 8 GB) without a usable step time.
  static constexpr int kMaxControlPointsLimit = 1 << 16;
  // Included angle theta_i of the control polygon at q_i (pi = straight), [B]'s thresholds; the
  // bend measure of [A] eq. 13 is c_i = (1 + cos theta_i) / 2. Insert below insertAngle, remove above
  // removeAngle: 0 < insertAngle < removeAngle < pi gives the hysteresis that stops flicker.
  double insertAngle = 140.0 * 3.14159265358979323846 / 180.0;  // rad (c = 0.117)
  double removeAngle = 160.0 * 3.14159265358979323846 / 180.0;  // rad (c = 0.030)
  // A knot is removed only if the curve (and the rest curve) move by at most this much. m, > 0.
  double removalErrorBound = 1.0e-4;
  // ... and only if the velocity field moves by at most this much (m/s, > 0). Without it a removal in
  // a part of the rope whose motion the coarser spline cannot carry (an impact, a whip) changed that
  // motion (and, before removal restored momentum, a moving rope's momentum by 2%).
  double removalVelocityErrorBound = 1.0e-3;
  RemovalCriterion removalCriterion = RemovalCriterion::kMechanicalOutOfContact;
  // kMechanical's relative bound, dimensionless, in (0, 1). Each measure's L2 error over the changed
  // spans may be this fraction of the measure's size there, plus a floor so that a field that is
  // zero (a still or straight rope) does not block removal by rounding: this fraction of
  // removalVelocityErrorBound (velocity, m/s) and of removalErrorBound / l^2 (curvature, 1/m),
  // l = the rest length of the changed spans. Not used by kPolygon.
  // Why 1e-4: the test sees one instant, and a vibrating rope's state passes it now and then when
  // its modes happen to combine into a smoother field. Measured, first three modes of a taut string
  // and of a rope hanging from one end, from 16 control points (fixed 16: within 0.07 % and 0.42 %):
  // 1e-4 within 0.20 % and 0.43 %, 3e-4 within 0.48 % and 0.48 % (before the geometric stiffness
  // counted only the tangent's turn); straight and still, both ropes are
  // coarsened to 4 control points either way.
  double removalRelativeError = 1.0e-4;
  // No knot span is split below twice this rest length, no interaction knot is placed closer
  // than this to an existing knot, and no knot within twice this of an interaction is removed (a
  // hysteresis for contacts that slide) (about a rope diameter: finer spans resolve nothing physical,
  // see StretchingQuadrature::kLockingFree). m, > 0.
  double minKnotSpacing = 5.0e-3;

  // Cross-section area (m^2), linear density (kg/m), EA (N) and EI (N m^2) with the sentinels resolved.
  double area() const;
  double effectiveLinearDensity() const;
  double axialStiffness() const;
  double effectiveBendingStiffness() const;

  // Throws InvalidArgument naming the field ("settings.radius", ...) for any value outside the
  // ranges documented above, NaN or infinity included.
  void validate() const;
};

}  // namespace rope
