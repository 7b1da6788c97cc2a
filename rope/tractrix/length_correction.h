// SPDX-License-Identifier: MIT
#pragma once
// Not API: installed only because rope/tractrix/tractrix_rope.h holds its workspace (the setting is
// TractrixSettings::lengthCorrection).
//
// Keeping a tractrix spline's curve length (beyond [B]). The tractrix pass keeps the control
// polygon's sides, but the curve is shorter than its polygon where the polygon bends ([B] §2.2), and
// subdivision cuts corners (shortening the polygon) while leaving the curve as it is. The tractrix
// then keeps the shorter polygon, so a rope dragged round tight bends loses length step after step
// (measured: [B]'s TRX_SD_MRG lost up to 16.8 % on a 270° loop, 22.6 % on `ropesim tractrix`).
//
// The correction (docs/method.md §14) re-lays the polygon from its leading point q_0,
// keeping every side's direction u_i and scaling side i by (1 + c w_i):
//   q_0' = q_0,   q_{i+1}' = q_i' + (1 + c w_i) |q_{i+1} - q_i| u_i,
// so q_i' = q_i + c D_i with D_i = sum_{k<i} w_k (q_{k+1} - q_k): the new polygon is linear in c, the
// curve is C + c C_D, and its length L(c) = integral |C' + c C_D'| ds is convex in c. Newton's method
// on L(c) = target converges in a few iterations (derivative L'(c) = integral t . C_D' ds). Each
// iteration is one pass over the quadrature points with the basis derivatives computed once: O(n).
//
// The weights put the change where the length went missing: w_i = 1/20 + (tau_i + tau_{i+1}) / pi,
// tau_j the turning angle pi - theta_j at interior corner j (0 at the ends). Lengthening the two sides
// of a bent corner pushes the corner outwards, which is where the curve cut inside it, and moves the
// rest of the chain by w l (u_in + u_out), small for a sharp corner. The constant part spreads what is
// left evenly, so that a straight polygon can still be corrected. The leading point never moves: the
// rope still follows its leader.
//
// What it does not fix: the coarse polygon's tractrix cuts inside tight bends (a chain of long rigid
// sides dragged round a circle spirals inwards), so the spline rope's shape departs from an exact
// follow-the-leader rope by much more than its length error, with or without the correction
// (measured against a 2000-segment TRX on the same paths, largest deviation over the run: 270° loop
// with a 5 m rope 1.31 m uncorrected, 1.54 m corrected; figure eight with 1.5 m, 0.78 m and 0.92 m;
// sweep circle 0.62 m and 0.70 m; the mean deviation over the loop falls from 0.76 m to 0.66 m).

#include <vector>

#include "rope/common/types.h"
#include "rope/spline/knot_vector.h"

namespace rope {

struct LengthCorrectionResult {
  bool applied = false;      // false: the polygon was left as it was (already within tolerance, or no
                             // admissible correction; see `feasible`)
  bool feasible = true;      // false: the correction would have shrunk a side below minSideFactor of
                             // itself or did not converge; the polygon is unchanged
  int iterations = 0;        // Newton iterations
  double scale = 0.0;        // c
  double lengthBefore = 0.0; // m, curve length on entry (the quadrature below)
  double lengthAfter = 0.0;  // m, curve length on return
};

struct LengthCorrectionOptions {
  int gaussPoints = 8;            // Gauss–Legendre points per knot span, 1..kMaxGaussPoints
  double tolerance = 1e-12;       // relative: stop once |L - target| <= tolerance * target
  int maxIterations = 20;
  double minSideFactor = 0.5;     // no side may shrink below this fraction of itself in one call
};

// Scratch space a caller may keep between calls so that a step allocates nothing.
struct LengthCorrectionWorkspace {
  std::vector<double> sideWeight;
  PointList offset;
  PointList curveDerivative;   // C' at the quadrature points
  PointList offsetDerivative;  // C_D' at the quadrature points
  std::vector<double> weight;  // quadrature weight times the half span length
};

// Restores the curve (knots, points) to targetLength (m, > 0) by re-laying points as described above.
// points[0] is the leading point and does not move. lengthBefore/lengthAfter are the curve's length
// in the same rule as arcLength() with options.gaussPoints points and one piece per span (to
// rounding), so a caller needs no separate measurement. The caller guarantees a valid, finite pair
// with distinct consecutive points and gaussPoints in range (it is the tractrix rope's own state);
// this hot path re-checks nothing.
LengthCorrectionResult restoreCurveLength(const KnotVector& knots, PointList& points, double targetLength,
                                          const LengthCorrectionOptions& options,
                                          LengthCorrectionWorkspace& workspace);
LengthCorrectionResult restoreCurveLength(const KnotVector& knots, PointList& points, double targetLength,
                                          const LengthCorrectionOptions& options = {});

}  // namespace rope
