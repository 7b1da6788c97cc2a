// SPDX-License-Identifier: MIT
#pragma once
// Adaptivity criteria on the control polygon ([A] §4, [B] §3; docs/method.md §10). Pure functions; Rod::step()
// applies them after each integration step (rod_adaptivity.cpp).
//
// Insertion: the polygon side q_i q_{i+1} is refined when the bend measure c ([A] eq. 13) at either of
// its ends exceeds the insertion threshold. [A] asks for both ends; either is used here because a
// single sharp corner (at a pin or a point load) must be refined too. The side corresponds to the
// parameter interval between the Greville abscissae of q_i and q_{i+1}; the knot goes to the middle of
// the knot span that contains the middle of that interval.
// Removal: an interior knot is removed when the polygon is straight around every control point the
// removal changes (c < removal threshold), the removal error is within the bound, and the polygon after
// removal would not immediately qualify for re-insertion (c < insertion threshold): the hysteresis
// between the two thresholds plus this look-ahead keeps knots from flickering.
// Rest curve: insertion refines it exactly (same plan). Removal is applied to it with the same plan
// too, and is allowed only if the rest curve moves by at most the same bound: a straight rest curve
// parametrised by arclength is linear in s and is removed exactly, so the material never changes; a
// curved rest curve keeps the knots it needs to stay within the bound. Knots at interaction points
// (pins, this step's loads) and knots whose removal would move a pinned point are kept.

#include <vector>

#include "rope/common/fixed_vector.h"
#include "rope/common/types.h"
#include "rope/rod/rod_integrals.h"
#include "rope/spline/knot_removal.h"
#include "rope/spline/knot_vector.h"

namespace rope {

// Greville abscissa of control point i: (s_{i+1} + ... + s_{i+d}) / d.
double grevilleAbscissa(const KnotVector& knots, int i);

// bend[i] = c_i for 1 <= i <= n-2, 0 at the ends; bend is resized to points.size().
void bendMeasures(const PointList& points, std::vector<double>& bend);

// Knot spans (ascending, unique) whose middle gets a knot by the curvature criterion.
void curvatureInsertionSpans(const KnotVector& knots, const std::vector<double>& bend,
                             double insertThreshold, std::vector<int>& spans);

// The values a removal plan would produce around the removed knot, and what they would be with the
// knot inserted again: max distance = the removal's error for this per-control-point field (by the
// convex hull property a bound on the field's change along the curve). Cost O(d).
struct LocalRemoval {
  // The window: control points span - d - 2 .. span + 3 (at most d + 6), held in place.
  using Window = FixedVector<Vec3, kMaxDegree + 6>;
  int offset = 0;          // global index of after[0]
  Window after;            // removed values at global indices offset .. offset + after.size() - 1
  // (removed values with the knot inserted again) - values, at global indices offset ..
  // offset + change.size() - 1 of the array before removal; zero everywhere else.
  Window change;
  double error = 0.0;      // max |change|
};
LocalRemoval localRemoval(const KnotRemoval& plan, const PointList& values);

// How well the coarser spline represents the state's mechanics (RemovalCriterion::kMechanical,
// docs/method.md §10). With dq, dv the removal's change of the points and velocities (knot inserted
// again), summed over the knot spans where it changes the curve:
//   velocity   dv^T M dv  against (v - v_mean)^T M (v - v_mean)   (M: mass matrix, kg)
//              dv^T G dv  against v^T G v   (G = int b_i'' b_j'' / l0'^3 ds: the field's curvature,
//                                           blind to translation and rotation)
//   curvature  EI dq^T G dq + sum_g EA e_g w1_g |dC'_g|^2  (bending, and the tension's geometric
//              stiffness)  against EI q^T G q + EA sum_g w0_g e_g^2  (the internal energy there)
//   strain     sum_g w0_g de_g^2 against sum_g w0_g e_g^2 (Green–Lagrange e at the stretching
//              points): reported, not part of worst() (see adaptivity.cpp)
// each as the ratio sqrt(err) / (relative * sqrt(size) + floor), floors from MechanicsBounds scaled
// to the region's mass and rest length: the removal keeps the mechanics when worst() <= 1. Inputs
// are the fields before removal and the local removals of the points and velocities with the same
// plan. O(d^2) per span touched, about 2d + 2 spans.
struct RemovalMechanics {
  double velocity = 0.0;
  double curvature = 0.0;
  double strain = 0.0;
  double worst() const;  // max(velocity, curvature)
};
struct MechanicsBounds {
  double relative = 1e-4;        // RodSettings::removalRelativeError
  double axialStiffness = 0.0;   // N, EA
  double positionFloor = 1e-8;   // m: relative * removalErrorBound
  double velocityFloor = 1e-7;   // m/s: relative * removalVelocityErrorBound
};
RemovalMechanics removalMechanics(const RodIntegrals& integrals, const PointList& points,
                                  const PointList& velocities, const LocalRemoval& pointRemoval,
                                  const LocalRemoval& velocityRemoval, const MechanicsBounds& bounds);

}  // namespace rope
