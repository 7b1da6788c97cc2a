// SPDX-License-Identifier: MIT
// Rod: knot insertion and removal, explicit and adaptive ([A] §3.1, §4; docs/method.md §2–§3, §10).
#include <algorithm>
#include <cmath>
#include <string>

#include "rope/common/error.h"
#include "rope/rod/adaptivity.h"
#include "rope/rod/insertion_relaxation.h"
#include "rope/rod/rod.h"
#include "rope/spline/control_polygon.h"
#include "rope/spline/knot_insertion.h"
#include "rope/spline/knot_removal.h"

namespace rope {

namespace {

// What a removal asks of the side its sweep runs from, except the length error that picks the side.
struct RemovalLimits {
  double shape = 0.0;            // m: the rest curve's change, and the curve's where nothing caps it
  double curveShape = 0.0;       // m: the curve's change (shape, or less where limitShapeChange caps it)
  double velocity = 0.0;         // m/s: the velocity field's change
  double insertThreshold = 0.0;  // bend measure above which the coarser polygon would refine at once
  bool mechanical = false;       // RemovalCriterion::kMechanical applies in this step
  MechanicsBounds mechanics;
};

struct RemovalSide {
  bool passes = false;
  LocalRemoval points, velocities;  // the sweep applied to the state (filled as far as the checks got)
};

// The checks of one side (plan.chosen), cheapest first. The plan's side is picked later by the
// length errors, which cost far more (a Gauss integral over the window, both sides): a candidate is
// given them only if one side could pass, so a rope whose candidates all fail (a vibrating one under
// kMechanical: 60 % of a pendulum's step went into length errors that were never used) skips them.
RemovalSide checkSide(const KnotRemoval& plan, const PointList& rest, const PointList& points,
                      const PointList& velocities, const RodIntegrals& integrals, const RemovalLimits& limits) {
  RemovalSide side;
  if (!(plan.chosenShapeError() <= limits.curveShape)) return side;
  if (!(localRemoval(plan, rest).error <= limits.shape)) return side;
  // Look ahead: the polygon after removal must not qualify for insertion at once.
  side.points = localRemoval(plan, points);
  for (int i = 1; i + 1 < static_cast<int>(side.points.after.size()); ++i) {
    if (!(bendMeasure(side.points.after.data(), side.points.after.size(), i) <= limits.insertThreshold)) return side;
  }
  // The velocity field follows the same removal sweep and is just as inexact; where it moves by more
  // than the bound (an impact, a whip), the coarser spline cannot carry the motion and the rope's
  // momentum would change with it.
  side.velocities = localRemoval(plan, velocities);
  if (!(side.velocities.error <= limits.velocity)) return side;
  // kMechanical: the bounds above are absolute, and a small vibration or a gentle load moves nothing
  // by much; the coarser spline must also carry the motion and the internal energy relative to their
  // own size here, or the rope would vibrate and sag as a coarser, different rope.
  if (limits.mechanical &&
      !(removalMechanics(integrals, points, velocities, side.points, side.velocities, limits.mechanics).worst() <= 1.0)) {
    return side;
  }
  side.passes = true;
  return side;
}

RemovalSide checkSide(KnotRemoval plan, KnotRemoval::Side chosen, const PointList& rest, const PointList& points,
                      const PointList& velocities, const RodIntegrals& integrals, const RemovalLimits& limits) {
  plan.chosen = chosen;
  return checkSide(plan, rest, points, velocities, integrals, limits);
}

}  // namespace

void Rod::insertKnotUnchecked(double s, StepReport* report) {
  const KnotInsertion plan = planKnotInsertion(knots_, s);
  // Only the reduced stretching rule's energy depends on the knots (insertion_relaxation.h).
  const bool reduced = integrals_.stretchingQuadrature() == StretchingQuadrature::kLockingFree;
  // Only in a rope that was free in the step (freeLastStep_): one in contact or held by loads and
  // springs is not a conservative system anyway (contact and spring damping), and the relaxation,
  // which knows nothing of what holds it, moves it against that. Measured with relaxation in contact
  // too: a rope thrown fast across another passed through it (RopeRopeContactScenario.FastRope...),
  // and a cable dropped on a kinematic rope sank 3.2 mm into it where its test allows 2 mm.
  const bool relax = reduced && report != nullptr && freeLastStep_;
  const double before = relax ? stretchingEnergy() + bendingEnergy() : 0.0;
  trialValid_ = false;
  restartHistory();  // the internal impulses are per control point of the old basis
  knots_.insertValue(s);
  // The same linear map for every per-control-point field: the curve, its velocity field and the rest
  // metric are exactly unchanged, so mass, momentum and the kinetic, gravity and bending energies are too.
  plan.apply(points_);
  plan.apply(velocities_);
  plan.apply(rest_);
  integrals_.afterInsertion(plan, knots_, rest_);
  if (report != nullptr) ++report->insertions;
  if (!relax) return;
  // The stretching rule's new points may see a strain the coarser rope held no energy for: the points
  // whose basis functions reach the two new spans (k - d .. k + 1 after insertion) give it back.
  const double excess = stretchingEnergy() + bendingEnergy() - before;
  if (!(excess > 0.0)) return;
  const double h = 1.0;  // the rows' right-hand sides are not used
  relaxationRows_.clear();
  for (const Pin& pinned : pins_) {
    relaxationRows_.push_back(pinRows(knots_, points_, velocities_, pinned.parameter, pinned.target, h));
    if (pinned.isClamp())
      relaxationRows_.push_back(clampTangentRows(knots_, points_, velocities_, pinned.parameter, pinned.direction, h));
  }
  const InsertionRelaxation relaxation = relaxInsertion(
      knots_, integrals_, settings_.axialStiffness(), excess, plan.span - degree(), plan.span + 1, relaxationRows_,
      pointMasses_, points_);
  report->maxInsertionRelaxation = std::max(report->maxInsertionRelaxation, relaxation.displacement);
  report->unrelaxedInsertionEnergy += relaxation.remaining;
}

void Rod::insertKnot(double s) {
  validateParameter(s);
  // Found by fuzzing: an interior knot of multiplicity degree + 1 disconnects the curve, leaving one
  // rod of two pieces that no longer meet (evaluation at s then belongs to one of them); cut() is
  // the way to make two ropes.
  if (knots_.multiplicity(s) >= degree() && s > beginParameter() && s < endParameter()) {
    throw InvalidArgument("s", formatValue(s),
                          "already has multiplicity degree = " + std::to_string(degree()) +
                              ": one more would split the rope in two (use cut)");
  }
  requireResolvableKnot(s);
  insertKnotUnchecked(s);  // planKnotInsertion validates the rest (strictly inside, multiplicity)
}

RemovalReport Rod::removeKnot(double s) {
  const KnotRemoval plan = planKnotRemoval(knots_, points_, s);
  if (controlPointCount() - 1 < static_cast<int>(pins_.size())) {
    throw InvalidArgument("s", formatValue(s), "removal would leave fewer control points than pins");
  }
  RemovalReport report;
  report.positionError = plan.chosenShapeError();
  report.restError = localRemoval(plan, rest_).error;
  report.velocityError = localRemoval(plan, velocities_).error;
  // The correction is added to control points, so it moves the field by at most its size.
  report.velocityError += applyRemoval(plan);
  return report;
}

Vec3 Rod::spanMomentum(int first, int last) const {
  const int local = degree() + 1;
  Vec3 momentum = Vec3::Zero();
  for (int j = std::max(0, first); j <= std::min(integrals_.spanCount() - 1, last); ++j) {
    const SpanView span = integrals_.span(j);
    for (int a = 0; a < local; ++a) momentum += span.gravity[a] * velocities_[static_cast<size_t>(j + a)];
  }
  return momentum;
}

double Rod::applyRemoval(const KnotRemoval& plan) {
  trialValid_ = false;
  restartHistory();
  // The sweep changes the control points first..last (numbered after removal; last + 1 leaves), so
  // the velocity field changes only on the spans that carry them: fine spans first-d .. last+1 before,
  // coarse spans first-d .. last after (the merged span among them); every other span and its weights
  // are the same before and after.
  const int d = plan.degree;
  const int first = plan.span - d + 1;
  const int last = plan.span - plan.multiplicityAfter - 1;
  const Vec3 before = spanMomentum(first - d, last + 1);
  knots_.eraseAt(plan.knotIndex);
  plan.apply(points_);
  plan.apply(velocities_);
  plan.apply(rest_);
  integrals_.afterRemoval(plan, knots_, rest_);
  // Only for a free rope: a rope held by pins or touched (contacts, attachments, loads: this step's
  // interactions) does not keep its momentum anyway, its constraints absorb the sweep's change, and
  // the correction, spread over the whole rope, pushed the held parts against them (measured: a held
  // knot tightened 6 % where its scene allows 5 %, a rope on a capstan crept at 2.4e-6 m/s).
  if (last < first || !pins_.empty() || !interactions_.empty()) return 0.0;
  // Why: the sweep reproduces the velocity field only up to its removal error, and that error has a
  // non-zero mean, so each removal changed the rope's momentum (measured: 2.1e-4 of a flung rope's
  // momentum after its removals). The momentum is g^T v (g_i = mu int b_i l0' ds, the rows of M
  // summed: M 1 = g); the correction dv of least kinetic energy dv^T M dv / 2 with g^T dv = dP is
  // M^-1 g dP / (g^T M^-1 g) = 1 dP / m, a uniform velocity: exact to rounding, and smaller at each
  // control point than any correction confined to the changed ones (which, like a mass-matrix L2
  // projection of the field, disturbed ropes held in contact: docs/method.md §10).
  const Vec3 after = spanMomentum(first - d, last);
  const double total = mass();
  if (!(total > 0.0)) return 0.0;
  const Vec3 correction = (before - after) / total;
  for (Vec3& v : velocities_) v += correction;
  return correction.norm();
}

double Rod::shapeChangeLimit(double from, double to, double bound) const {
  // The tightest cap queued (limitShapeChange) on the parameters the removal changes.
  const auto first = std::lower_bound(shapeLimits_.begin(), shapeLimits_.end(), from,
                                      [](const ShapeLimit& limit, double s) { return limit.parameter < s; });
  for (auto it = first; it != shapeLimits_.end() && it->parameter < to; ++it) bound = std::min(bound, it->change);
  return bound;
}

bool Rod::isNearInteraction(double s) const {
  // Within twice minKnotSpacing (rest length) of a point something acts on: the knot that carries that
  // point's local freedom. An exact match alone is not enough: a contact slides a little every step,
  // and its old knot would be removed while the new parameter is still too close for a new knot, so
  // the knot would flicker out and in again, kicking the rope each time (measured: a rope heap never
  // came to rest, kinetic energy 5e-5 J instead of 3e-6 J). Twice the insertion's own distance (a knot
  // goes to an interaction only if none is within minKnotSpacing) is a hysteresis: with the same
  // distance for both, the 2 m heap at rest still made 1,199 insertions and as many removals from 6
  // to 40 s as its contacts slid by less than a knot spacing; with twice it, 25.
  const int k = knots_.findSpan(s);
  const double parameterLength = knots_[k + 1] - knots_[k];
  const double restPerParameter = integrals_.span(k - degree()).restLength / parameterLength;
  for (double t : interactions_)
    if (std::abs(t - s) * restPerParameter < 2.0 * settings_.minKnotSpacing) return true;  // hysteresis
  return false;
}

void Rod::adapt(StepReport& report) {
  if (!settings_.adaptive) return;
  const int d = degree();
  const double insertThreshold = bendMeasureFromAngle(settings_.insertAngle);
  const double removeThreshold = bendMeasureFromAngle(settings_.removeAngle);
  const double spacing = settings_.minKnotSpacing;
  const int maxCount = settings_.maxControlPoints;

  // 1. Interaction points get a knot, so that local degrees of freedom exist there ([A] §4).
  for (double s : interactions_) {
    if (controlPointCount() >= maxCount) break;
    if (knots_.multiplicity(s) > 0) continue;
    const int k = knots_.findSpan(s);
    const double parameterLength = knots_[k + 1] - knots_[k];
    const double restPerParameter = integrals_.span(k - d).restLength / parameterLength;
    const double nearest = std::min(s - knots_[k], knots_[k + 1] - s) * restPerParameter;
    if (nearest < spacing) continue;
    insertKnotUnchecked(s, &report);
  }

  // 2. Curvature criterion ([A] eq. 13): refine where the control polygon bends.
  bendMeasures(points_, bend_);
  curvatureInsertionSpans(knots_, bend_, insertThreshold, spans_);
  for (auto it = spans_.rbegin(); it != spans_.rend(); ++it) {  // right to left: lower spans keep their index
    if (controlPointCount() >= maxCount) break;
    const int k = *it;
    if (integrals_.span(k - d).restLength < 2.0 * spacing) continue;
    insertKnotUnchecked(0.5 * (knots_[k] + knots_[k + 1]), &report);
  }

  // 3. Removal where the polygon is straight and the error small, right to left.
  bendMeasures(points_, bend_);
  const double bound = settings_.removalErrorBound;
  const bool mechanical = settings_.removalCriterion == RemovalCriterion::kMechanical ||
                          (settings_.removalCriterion == RemovalCriterion::kMechanicalOutOfContact && !contactLastStep_);
  RemovalLimits limits;
  limits.shape = bound;
  limits.curveShape = bound;
  limits.velocity = settings_.removalVelocityErrorBound;
  limits.insertThreshold = insertThreshold;
  limits.mechanical = mechanical;
  limits.mechanics.relative = settings_.removalRelativeError;
  limits.mechanics.axialStiffness = settings_.axialStiffness();
  limits.mechanics.positionFloor = settings_.removalRelativeError * bound;
  limits.mechanics.velocityFloor = settings_.removalRelativeError * settings_.removalVelocityErrorBound;
  for (int r = controlPointCount() - 1; r >= d + 1; --r) {
    const int n = controlPointCount();
    if (n - 1 < settings_.minControlPoints || n - 1 <= static_cast<int>(pins_.size())) break;
    if (r > n - 1) continue;
    const double t = knots_[r];
    if (!(t > beginParameter() && t < endParameter())) continue;
    if (knots_.multiplicity(t) != 1 || isNearInteraction(t)) continue;
    // Removal moves the curve on the support of the changed control points, (s_{r-d}, s_{r+d}): keep
    // pinned points exactly where the constraint put them.
    bool pinned = false;
    for (const Pin& p : pins_)
      pinned = pinned || (p.parameter > knots_[std::max(0, r - d)] && p.parameter < knots_[std::min(knots_.size() - 1, r + d)]);
    if (pinned) continue;
    bool straight = true;
    for (int i = std::max(1, r - d - 1); i <= std::min(n - 2, r); ++i)
      straight = straight && bend_[static_cast<size_t>(i)] < removeThreshold;
    if (!straight) continue;
    // Most straight-looking candidates in a bent rope fail the shape bound: reject those on the cheap
    // shape errors alone before integrating length errors (profile of the knot scene: 28 % of the
    // step in planKnotRemoval before).
    limits.curveShape = shapeLimits_.empty()
                            ? bound
                            : shapeChangeLimit(knots_[std::max(0, r - d)], knots_[std::min(knots_.size() - 1, r + d)], bound);
    const KnotRemoval shape = planKnotRemovalShape(knots_, points_, t);
    if (!(std::min(shape.shapeError[0], shape.shapeError[1]) <= limits.curveShape)) continue;
    // Every check but the length error, on both sides: the length errors only where one could pass
    // (checkSide), and then the side they pick must (the same computation as its check here).
    const RemovalSide left = checkSide(shape, KnotRemoval::kFromLeft, rest_, points_, velocities_, integrals_, limits);
    const RemovalSide right = checkSide(shape, KnotRemoval::kFromRight, rest_, points_, velocities_, integrals_, limits);
    if (!left.passes && !right.passes) continue;
    const KnotRemoval plan = planKnotRemoval(knots_, points_, t);
    const RemovalSide& chosen = plan.chosen == KnotRemoval::kFromLeft ? left : right;
    if (!chosen.passes) continue;
    const double velocityError = chosen.velocities.error;
    const double correction = applyRemoval(plan);
    ++report.removals;
    report.maxRemovalError = std::max(report.maxRemovalError, plan.chosenShapeError());
    report.maxRemovalVelocityError = std::max(report.maxRemovalVelocityError, velocityError + correction);
    // Indices <= r are what the rest of the sweep reads; refresh the ones this removal changed.
    const int count = controlPointCount();
    bend_.resize(static_cast<size_t>(count));
    for (int i = std::max(1, r - d - 3); i <= std::min(count - 2, r + 1); ++i)
      bend_[static_cast<size_t>(i)] = bendMeasure(points_, i);
  }
}

}  // namespace rope
