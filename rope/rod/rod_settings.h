#pragma once
// What a user configures for a dynamic rod ([A] §3.2–4, spec §2–3): material, discretisation and
// adaptivity. SI units throughout. The rod copies the settings at creation; what a step changes
// (control points, velocities, knots, pins) lives in the Rod itself.

#include "rope/common/types.h"

namespace rope {

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
  // Rayleigh damping D = massDamping * M + stiffnessDamping * K (spec §2). Both >= 0.
  double massDamping = 0.0;        // 1/s
  double stiffnessDamping = 0.0;   // s
  Vec3 gravity = Vec3(0.0, -9.81, 0.0);  // m/s^2, finite (y up, as in Bullet's demos)

  // ---- discretisation ----
  int degree = 3;                  // 1..kMaxDegree (cubic as in [A]); bending needs degree >= 2.
  int initialControlPoints = 16;   // ropes created from a segment; in [minControlPoints, maxControlPoints]

  // ---- adaptivity ([A] §4, spec §3) ----
  bool adaptive = true;            // false: the knot vector only changes on explicit request
  int minControlPoints = 4;        // >= degree + 1
  int maxControlPoints = 128;      // >= minControlPoints
  // Included angle theta_i of the control polygon at q_i (pi = straight), [B]'s thresholds; the
  // bend measure of [A] eq. 13 is c_i = (1 + cos theta_i) / 2. Insert below insertAngle, remove above
  // removeAngle: 0 < insertAngle < removeAngle < pi gives the hysteresis that stops flicker.
  double insertAngle = 140.0 * 3.14159265358979323846 / 180.0;  // rad (c = 0.117)
  double removeAngle = 160.0 * 3.14159265358979323846 / 180.0;  // rad (c = 0.030)
  // A knot is removed only if the curve (and the rest curve) move by at most this much. m, > 0.
  double removalErrorBound = 1.0e-4;
  // No knot span is split below twice this rest length, and no interaction knot is placed closer
  // than this to an existing knot. m, > 0.
  double minKnotSpacing = 1.0e-3;

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
