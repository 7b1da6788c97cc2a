// SPDX-License-Identifier: MIT
#include "rope/rod/rod.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>

#include "rope/common/error.h"
#include "rope/common/prefetch.h"
#include "rope/rod/bending_energy.h"
#include "rope/rod/stretching_energy.h"
#include "rope/spline/arc_length.h"
#include "rope/spline/bspline_basis.h"
#include "rope/spline/bspline_curve.h"
#include "rope/spline/curve_interpolation.h"

namespace rope {

namespace {

// No arithmetic on the values (inf - inf would raise FE_INVALID under FP traps).
bool allFiniteEntries(const double* values, int count) {
  for (int i = 0; i < count; ++i)
    if (!std::isfinite(values[i])) return false;
  return true;
}

// The names are built only for a failing value: these checks run for every load, every step.
void requireFiniteVector(const std::string& name, const Vec3& value) {
  if (allFiniteEntries(value.data(), 3)) return;
  for (int axis = 0; axis < 3; ++axis) requireFinite(name + "[" + std::to_string(axis) + "]", value[axis]);
}

void requireFiniteMatrix(const std::string& name, const Eigen::Matrix3d& value) {
  if (allFiniteEntries(value.data(), 9)) return;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      requireFinite(name + "(" + std::to_string(r) + "," + std::to_string(c) + ")", value(r, c));
}

void requirePoints(const std::string& name, const PointList& points, size_t count) {
  if (points.size() != count) {
    throw InvalidArgument(name + ".size()", std::to_string(points.size()),
                          "must be " + std::to_string(count));
  }
  for (size_t i = 0; i < points.size(); ++i) requireFiniteVector(name + "[" + std::to_string(i) + "]", points[i]);
}

bool allFinite(const PointList& points) {
  for (const Vec3& p : points)
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) return false;
  return true;
}

// Greville abscissae of a straight rest curve along x: C0(s) = s e_x exactly (linear precision), so
// l0'(s) = 1 and s is the rest arclength.
PointList straightRest(const KnotVector& knots) {
  const int d = knots.degree();
  PointList rest(static_cast<size_t>(knots.controlPointCount()), Vec3::Zero());
  for (int i = 0; i < knots.controlPointCount(); ++i) {
    double sum = 0.0;
    for (int k = 1; k <= d; ++k) sum += knots[i + k];
    rest[static_cast<size_t>(i)].x() = sum / d;
  }
  return rest;
}

}  // namespace

// ---- construction ----

Rod::Rod(const RodSettings& settings, KnotVector knots, PointList points, PointList velocities,
         PointList rest, int gaussCount)
    : settings_(settings),
      knots_(std::move(knots)),
      points_(std::move(points)),
      velocities_(std::move(velocities)),
      rest_(std::move(rest)) {
  integrals_.build(knots_, rest_, settings_.effectiveLinearDensity(), settings_.effectiveBendingStiffness(),
                   gaussCount, settings_.stretchingQuadrature);
}

Rod Rod::fromSegment(const RodSettings& settings, const Vec3& a, const Vec3& b) {
  settings.validate();
  requireFiniteVector("a", a);
  requireFiniteVector("b", b);
  if (!((b - a).norm() > 0.0)) throw InvalidArgument("b", "a", "must differ from a");
  const int n = settings.initialControlPoints;
  KnotVector knots = KnotVector::clampedUniform(settings.degree, n, 0.0, settings.restLength);
  PointList rest = straightRest(knots);
  PointList points(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double u = rest[static_cast<size_t>(i)].x() / settings.restLength;
    points[static_cast<size_t>(i)] = a + u * (b - a);
  }
  return Rod(settings, std::move(knots), std::move(points), PointList(static_cast<size_t>(n), Vec3::Zero()),
             std::move(rest), RodIntegrals::exactGaussCount(settings.degree));
}

Rod Rod::fromCurve(const RodSettings& settings, const KnotVector& knots, const PointList& points,
                   RestShape restShape) {
  if (restShape != RestShape::kScaledToRestLength && restShape != RestShape::kAsGiven) {
    throw InvalidArgument("rest", std::to_string(static_cast<int>(restShape)), "is not a Rod::RestShape");
  }
  PointList rest = points;
  if (restShape == RestShape::kScaledToRestLength) {
    const double length = arcLength(knots, points, knots.validBegin(), knots.validEnd());
    if (!(length > 0.0)) throw InvalidArgument("points", "length 0", "curve must have a length");
    const double scale = settings.restLength / length;
    for (Vec3& p : rest) p *= scale;
  }
  // A curved rest metric makes the integrands non-polynomial: 4 more points than the exact rule keep
  // the quadrature error well below the discretisation error.
  const int gauss = RodIntegrals::exactGaussCount(settings.degree) + 4;
  return Rod(settings, knots, points, PointList(points.size(), Vec3::Zero()), std::move(rest), gauss);
}

Rod Rod::fromPolyline(const RodSettings& settings, const PointList& points, RestShape rest) {
  settings.validate();
  const Interpolation interpolation = interpolatePolyline(points, settings.degree);
  return fromCurve(settings, interpolation.curve.knots(), interpolation.curve.controlPoints(), rest);
}

Rod Rod::fromControlPoints(const RodSettings& settings, const KnotVector& knots, const PointList& points,
                           RestShape rest) {
  settings.validate();
  if (knots.degree() != settings.degree) {
    throw InvalidArgument("knots.degree()", std::to_string(knots.degree()), "must equal settings.degree");
  }
  requirePoints("points", points, static_cast<size_t>(knots.controlPointCount()));
  return fromCurve(settings, knots, points, rest);
}

Rod Rod::fromControlPoints(const RodSettings& settings, const KnotVector& knots, const PointList& points,
                           const PointList& restPoints) {
  settings.validate();
  if (knots.degree() != settings.degree) {
    throw InvalidArgument("knots.degree()", std::to_string(knots.degree()), "must equal settings.degree");
  }
  requirePoints("points", points, static_cast<size_t>(knots.controlPointCount()));
  requirePoints("restPoints", restPoints, static_cast<size_t>(knots.controlPointCount()));
  const int gauss = RodIntegrals::exactGaussCount(settings.degree) + 4;
  return Rod(settings, knots, points, PointList(points.size(), Vec3::Zero()), restPoints, gauss);
}

// ---- state access ----

void Rod::validateParameter(double s) const {
  requireFinite("s", s);
  if (!knots_.contains(s)) {
    throw InvalidArgument("s", formatValue(s),
                          "must be in [" + formatValue(beginParameter()) + ", " + formatValue(endParameter()) + "]");
  }
}

Vec3 Rod::position(double s) const { return curvePosition(knots_, points_, s); }
Vec3 Rod::velocity(double s) const { return curvePosition(knots_, velocities_, s); }
void Rod::positionsAt(const std::vector<double>& s, PointList& out) const { curvePositions(knots_, points_, s, out); }
void Rod::velocitiesAt(const std::vector<double>& s, PointList& out) const { curvePositions(knots_, velocities_, s, out); }

Vec3 Rod::tangent(double s) const {
  const Vec3 derivative = evaluateCurve(knots_, points_, s).firstDerivative;
  const double norm = derivative.norm();
  return norm > 0.0 ? Vec3(derivative / norm) : Vec3(Vec3::Zero());
}

double Rod::length() const { return arcLength(knots_, points_, beginParameter(), endParameter()); }

double Rod::restLength() const {
  double sum = 0.0;
  for (int j = 0; j < integrals_.spanCount(); ++j) sum += integrals_.span(j).restLength;
  return sum;
}

double Rod::maxStrain() const { return rope::maxStrain(integrals_, points_); }

double Rod::strain(double s) const {
  validateParameter(s);
  const double rest = evaluateCurve(knots_, rest_, s).firstDerivative.norm();
  const double current = evaluateCurve(knots_, points_, s).firstDerivative.norm();
  return rest > 0.0 ? current / rest - 1.0 : 0.0;
}

double Rod::restMetric(double s) const {
  validateParameter(s);
  return evaluateCurve(knots_, rest_, s).firstDerivative.norm();
}

namespace {

// The basis functions at s (span k - d ... k) for point masses; returns the first control point's index.
int basisAt(const KnotVector& knots, double s, BasisValues& basis) {
  const int k = knots.findSpan(s);
  evaluateBasis(knots, k, s, 0, basis);
  return k - knots.degree();
}

}  // namespace

double Rod::mass() const {
  double sum = 0.0;
  for (const auto& [s, m] : pointMasses_) sum += m;
  for (int j = 0; j < integrals_.spanCount(); ++j) {
    const SpanView span = integrals_.span(j);
    for (int a = 0; a < span.localCount; ++a) sum += span.gravity[a];
  }
  return sum;
}

Vec3 Rod::momentum() const {
  Vec3 sum = Vec3::Zero();
  for (int j = 0; j < integrals_.spanCount(); ++j) {
    const SpanView span = integrals_.span(j);
    for (int a = 0; a < span.localCount; ++a) sum += span.gravity[a] * velocities_[static_cast<size_t>(j + a)];
  }
  for (const auto& [s, m] : pointMasses_) sum += m * velocity(s);
  return sum;
}

double Rod::kineticEnergy() const {
  double sum = 0.0;
  for (int j = 0; j < integrals_.spanCount(); ++j) {
    const SpanView span = integrals_.span(j);
    for (int a = 0; a < span.localCount; ++a)
      for (int b = 0; b < span.localCount; ++b)
        sum += 0.5 * span.mass[a * span.localCount + b] *
               velocities_[static_cast<size_t>(j + a)].dot(velocities_[static_cast<size_t>(j + b)]);
  }
  for (const auto& [s, m] : pointMasses_) sum += 0.5 * m * velocity(s).squaredNorm();
  return sum;
}

double Rod::stretchingEnergy() const {
  return rope::stretchingEnergy(integrals_, points_, settings_.axialStiffness());
}

double Rod::bendingEnergy() const { return rope::bendingEnergy(integrals_, points_); }

double Rod::gravityEnergy() const {
  double sum = 0.0;
  for (int j = 0; j < integrals_.spanCount(); ++j) {
    const SpanView span = integrals_.span(j);
    for (int a = 0; a < span.localCount; ++a)
      sum -= span.gravity[a] * settings_.gravity.dot(points_[static_cast<size_t>(j + a)]);
  }
  for (const auto& [s, m] : pointMasses_) sum -= m * settings_.gravity.dot(position(s));
  return sum;
}

void Rod::setGravity(const Vec3& gravity) {
  requireFiniteVector("gravity", gravity);
  if (settings_.gravity == gravity) return;  // the common case in a world: nothing to invalidate
  settings_.gravity = gravity;
  trialValid_ = false;
}

void Rod::setControlPoints(const PointList& points) {
  requirePoints("points", points, points_.size());
  points_ = points;
  restartHistory();
  trialValid_ = false;
}

void Rod::setVelocities(const PointList& velocities) {
  requirePoints("velocities", velocities, velocities_.size());
  velocities_ = velocities;
  restartHistory();
  trialValid_ = false;
}

// ---- pins ----

int Rod::findPin(int id, bool clamp) const {
  for (size_t i = 0; i < pins_.size(); ++i) {
    if (pins_[i].id != id) continue;
    if (pins_[i].isClamp() != clamp) {
      throw InvalidArgument("id", std::to_string(id),
                            clamp ? "is a pin: use setPinTarget / releasePin"
                                  : "is a clamp: use setClampTarget / releaseClamp");
    }
    return static_cast<int>(i);
  }
  throw InvalidArgument("id", std::to_string(id), clamp ? "no such clamp" : "no such pin");
}

int Rod::constraintRowCount() const {
  int rows = 0;
  for (const Pin& p : pins_) rows += p.isClamp() ? 5 : 3;
  return rows;
}

int Rod::addPin(double s, const Vec3& target, const Vec3& direction) {
  for (const Pin& other : pins_) {
    if (other.parameter == s) {
      throw InvalidArgument("s", formatValue(s),
                            other.isClamp() ? "a clamp is already there" : "a pin is already there");
    }
  }
  Pin added;
  added.id = nextPinId_;
  added.parameter = s;
  added.target = target;
  added.direction = direction;
  const int rows = constraintRowCount() + (added.isClamp() ? 5 : 3);
  if (rows > 3 * controlPointCount()) {
    throw InvalidArgument(added.isClamp() ? "clamps" : "pins", std::to_string(rows) + " constraint rows",
                          "more than the rod's 3 x " + std::to_string(controlPointCount()) + " degrees of freedom");
  }
  requireIndependentPin(s);
  ++nextPinId_;
  pins_.push_back(added);
  trialValid_ = false;
  return added.id;
}

int Rod::pin(double s, const Vec3& target) {
  validateParameter(s);
  requireFiniteVector("target", target);
  return addPin(s, target, Vec3::Zero());
}

int Rod::pin(double s) {
  validateParameter(s);
  return pin(s, position(s));
}

void Rod::setPinTarget(int id, const Vec3& target) {
  const int index = findPin(id, false);
  requireFiniteVector("target", target);
  pins_[static_cast<size_t>(index)].target = target;
  trialValid_ = false;
}

void Rod::releasePin(int id) {
  pins_.erase(pins_.begin() + findPin(id, false));
  trialValid_ = false;
}

// ---- clamps ----

namespace {

// The unit vector along direction; "direction[c]" for a non-finite component, "direction" for zero.
// Scaled by its largest component first, so that tiny and huge (finite) vectors normalise exactly.
Vec3 unitDirection(const Vec3& direction) {
  requireFiniteVector("direction", direction);
  const double largest = direction.cwiseAbs().maxCoeff();
  if (!(largest > 0.0)) throw InvalidArgument("direction", "(0, 0, 0)", "must have a non-zero length");
  const Vec3 scaled = direction / largest;
  return scaled / scaled.norm();
}

}  // namespace

int Rod::clamp(double s, const Vec3& target, const Vec3& direction) {
  validateParameter(s);
  requireFiniteVector("target", target);
  return addPin(s, target, unitDirection(direction));
}

int Rod::clamp(double s) {
  validateParameter(s);
  const Vec3 derivative = evaluateCurve(knots_, points_, s).firstDerivative;
  if (!(derivative.cwiseAbs().maxCoeff() > 0.0)) {
    throw InvalidArgument("s", formatValue(s), "the curve has no tangent there (C'(s) = 0)");
  }
  return clamp(s, position(s), derivative);
}

void Rod::setClampTarget(int id, const Vec3& target, const Vec3& direction) {
  const int index = findPin(id, true);
  requireFiniteVector("target", target);
  const Vec3 unit = unitDirection(direction);
  pins_[static_cast<size_t>(index)].target = target;
  pins_[static_cast<size_t>(index)].direction = unit;
  trialValid_ = false;
}

void Rod::releaseClamp(int id) {
  pins_.erase(pins_.begin() + findPin(id, true));
  trialValid_ = false;
}

void Rod::addClampNeighbours(std::vector<double>& interactions) const {
  // Knot removal moves the curve only on the open support of the replaced control points, which
  // adaptivity keeps clear of every pin and clamp parameter; inside the valid range the change
  // vanishes at the support's ends with d-1 derivatives (simple knots), so C'(s) is kept too. At a
  // clamped end it is not: removing the first interior knot replaces q_1 and turns C'(begin) (for
  // the last interior knot, C'(end)). Marking the nearest distinct knot on either side of a clamp as
  // an interaction keeps it (adaptivity removes no knot near an interaction).
  for (const Pin& p : pins_) {
    if (!p.isClamp()) continue;
    const int k = knots_.findSpan(p.parameter);  // knots_[k] <= s < knots_[k+1] (or s = end)
    int below = k;
    while (below > degree() && !(knots_[below] < p.parameter)) --below;
    if (knots_[below] < p.parameter && knots_[below] > beginParameter()) interactions.push_back(knots_[below]);
    int above = k + 1;
    while (above < controlPointCount() && !(knots_[above] > p.parameter)) ++above;
    if (knots_[above] > p.parameter && knots_[above] < endParameter()) interactions.push_back(knots_[above]);
  }
}

// ---- point masses ----

void Rod::addPointMass(double s, double mass) {
  validateParameter(s);
  requirePositive("mass", mass);
  pointMasses_.emplace_back(s, mass);
  trialValid_ = false;
}

// ---- loads ----

void Rod::addForce(double s, const Vec3& force) {
  validateParameter(s);
  requireFiniteVector("force", force);
  loads_.push_back({s, force, false});
  trialValid_ = false;
}

void Rod::addImpulse(double s, const Vec3& impulse) {
  validateParameter(s);
  requireFiniteVector("impulse", impulse);
  loads_.push_back({s, impulse, true});
  trialValid_ = false;
}

void Rod::addSpring(double s, const Vec3& force, const Eigen::Matrix3d& stiffness,
                    const Eigen::Matrix3d& damping) {
  queueSpring(s, force, stiffness, damping, true);
}

void Rod::addSpringSample(double s, const Vec3& force, const Eigen::Matrix3d& stiffness,
                          const Eigen::Matrix3d& damping) {
  queueSpring(s, force, stiffness, damping, false);
}

void Rod::addTangentSpring(double s, const Vec3& force, const Eigen::Matrix3d& stiffness,
                           const Eigen::Matrix3d& damping) {
  queueSpring(s, force, stiffness, damping, true, 1);
}

void Rod::queueSpring(double s, const Vec3& force, const Eigen::Matrix3d& stiffness, const Eigen::Matrix3d& damping,
                      bool interaction, int derivative) {
  validateParameter(s);
  requireFiniteVector("force", force);
  requireFiniteMatrix("stiffness", stiffness);
  requireFiniteMatrix("damping", damping);
  // Only the symmetric part is meaningful for a potential/dissipative interaction.
  springs_.push_back({s, force, 0.5 * (stiffness + stiffness.transpose()), 0.5 * (damping + damping.transpose()),
                      interaction, derivative});
  trialValid_ = false;
}

void Rod::takeLoads(LoadQueue& queue) {
  // Copied, not exchanged: each side keeps its own buffers, so storage lent to the rod
  // (swapStepScratch) stays the rod's for the step, and a queue that is empty (the usual case
  // between steps) touches no memory.
  queue.loads.assign(loads_.begin(), loads_.end());
  queue.springs.assign(springs_.begin(), springs_.end());
  queue.marked.assign(markedInteractions_.begin(), markedInteractions_.end());
  loads_.clear();
  springs_.clear();
  markedInteractions_.clear();
  trialValid_ = false;
}

void Rod::addLoads(const LoadQueue& queue) {
  loads_.insert(loads_.end(), queue.loads.begin(), queue.loads.end());
  springs_.insert(springs_.end(), queue.springs.begin(), queue.springs.end());
  markedInteractions_.insert(markedInteractions_.end(), queue.marked.begin(), queue.marked.end());
  trialValid_ = false;
}

void Rod::clearLoads() {
  loads_.clear();
  springs_.clear();
  markedInteractions_.clear();
  pendingShapeLimits_.clear();
  trialValid_ = false;
}

// ---- step ----

namespace {

// Length of the curve with control points `points`, as the polyline through four chords per span
// (a lower bound, within 1e-3 relative for spans bent by less than a right angle).
double chordLength(const KnotVector& knots, const PointList& points) {
  double length = 0.0;
  for (int k = knots.degree(); k + 1 < knots.size() - knots.degree(); ++k) {
    const double a = knots[k], b = knots[k + 1];
    if (!(b > a)) continue;
    Vec3 previous = evaluateCurve(knots, points, a).position;
    for (const double t : {0.25, 0.5, 0.75, 1.0}) {
      const Vec3 next = evaluateCurve(knots, points, a + t * (b - a)).position;
      length += (next - previous).norm();
      previous = next;
    }
  }
  return length;
}

}  // namespace

bool Rod::overstretchedBy(const PointList& next) const {
  // The whole rope's length, not a local stretch: a slack or compressed rope with little bending
  // stiffness passes through zig-zag transients whose local stretch is large and harmless (the
  // catenary tests start that way); a step that makes the rope as a whole longer than
  // kMaxStepStretch times its rest length, and longer than it was, is garbage. A rope created
  // stretched may relax.
  // The control polygon is at least as long as the curve and the chords: a polygon within the limit
  // (every ordinary step) settles it in O(n) without evaluating the curve.
  double polygon = 0.0;
  for (size_t i = 1; i < next.size(); ++i) polygon += (next[i] - next[i - 1]).norm();
  if (!(polygon > kMaxStepStretch * restLength())) return false;
  const double after = chordLength(knots_, next);
  return after > kMaxStepStretch * restLength() && after > chordLength(knots_, points_);
}

StepReport Rod::step(double h) {
  StepReport report = solveTrial(h);
  if (report.ok) return commitTrial();
  clearLoads();
  report.controlPoints = controlPointCount();
  return report;
}

StepReport Rod::solveTrial(double h, bool relineariseInContact) {
  requirePositive("h", h);
  StepReport report;
  trialValid_ = false;
  bool solved = assembleAndSolve(h, report);
  trialRelinearisationTried_ = solved && needsRelinearisation(relineariseInContact);
  relinearisingInContact_ = relineariseInContact;
  if (trialRelinearisationTried_) {
    // One Newton correction: the same step with the stretching force linearised about the trial
    // (see linearisationExcess). It is kept if it relieves the stretch the first pass made; if not
    // (a Newton step from far off, or a failed solve), the first pass is solved again and kept.
    step_.relinearisationPoints = step_.newPoints;
    const double first = trialEnergy();
    StepReport corrected;
    const bool ok = assembleAndSolve(h, corrected, &step_.relinearisationPoints);
    if (!(ok && trialEnergy() < first)) solved = assembleAndSolve(h, report);
  }
  if (solved) {
    trialValid_ = true;
    trialStep_ = h;
  }
  report.controlPoints = controlPointCount();
  return report;
}

const PointList& Rod::trialVelocities() const {
  if (!trialValid_) throw InvalidArgument("trial", "none", "solveTrial() must have succeeded since the last change");
  return step_.newVelocities;
}

Vec3 Rod::trialVelocity(double s) const {
  validateParameter(s);
  return curvePosition(knots_, trialVelocities(), s);
}

void Rod::trialImpulseResponse(double s, int axis, double* response) const {
  validateParameter(s);
  if (axis < 0 || axis > 2) throw InvalidArgument("axis", std::to_string(axis), "must be 0, 1 or 2");
  trialImpulseResponse(s, Vec3::Unit(axis), response);
}

void Rod::trialImpulseResponse(double s, const Vec3& direction, double* response) const {
  validateParameter(s);
  requireFiniteVector("direction", direction);
  if (!trialValid_ || !solver_.ready()) {
    throw InvalidArgument("trial", "none", "solveTrial() must have succeeded on this rod since the last change");
  }
  const int n = controlPointCount();
  const int d = degree();
  BasisValues basis;
  const int first = basisAt(knots_, s, basis);
  std::fill(response, response + 3 * n, 0.0);
  for (int a = 0; a <= d; ++a)
    for (int c = 0; c < 3; ++c) response[3 * (first + a) + c] = basis.d[0][static_cast<size_t>(a)] * direction[c];
  // The scratch solver is logically const here: it only reuses the trial's Schur factor.
  const_cast<ConstrainedSolver&>(solver_).solveHomogeneous(step_.system, response, 3 * first);
}

void Rod::trialImpulseResponses(double s, double* responses) const {
  const double weight = 1.0;
  impulseResponses(&s, &weight, 1, responses, false);
}

void Rod::trialImpulseResponsesOnward(double s, double* responses) const {
  const double weight = 1.0;
  impulseResponses(&s, &weight, 1, responses, true);
}

void Rod::trialImpulseResponsesOnward(const double* s, const double* weights, int count, double* responses) const {
  if (count < 1 || count > kMaxResponsePoints) {
    throw InvalidArgument("count", std::to_string(count), "must be in 1.." + std::to_string(kMaxResponsePoints));
  }
  for (int j = 0; j < count; ++j) {
    if (knots_.contains(s[j]) && std::isfinite(weights[j])) continue;
    // The names are built only for the error (this runs for every coupling that acts).
    const std::string index = "[" + std::to_string(j) + "]";
    if (!knots_.contains(s[j])) {
      requireFinite("s" + index, s[j]);
      throw InvalidArgument("s" + index, formatValue(s[j]),
                            "must be in [" + formatValue(beginParameter()) + ", " + formatValue(endParameter()) + "]");
    }
    requireFinite("weights" + index, weights[j]);
  }
  impulseResponses(s, weights, count, responses, true);
}

void Rod::impulseResponses(const double* s, const double* weights, int count, double* responses, bool onward) const {
  for (int j = 0; j < count; ++j) validateParameter(s[j]);
  if (!trialValid_ || !solver_.ready()) {
    throw InvalidArgument("trial", "none", "solveTrial() must have succeeded on this rod since the last change");
  }
  const int n3 = 3 * controlPointCount();
  const int d = degree();
  BasisValues basis[kMaxResponsePoints];
  int firsts[kMaxResponsePoints];
  int first = controlPointCount();
  for (int j = 0; j < count; ++j) {
    firsts[j] = basisAt(knots_, s[j], basis[j]);
    first = std::min(first, firsts[j]);
  }
  std::fill(responses, responses + 3 * n3, 0.0);
  for (int axis = 0; axis < 3; ++axis) {
    double* response = responses + axis * n3;
    for (int j = 0; j < count; ++j) {
      for (int a = 0; a <= d; ++a) response[3 * (firsts[j] + a) + axis] += weights[j] * basis[j].d[0][static_cast<size_t>(a)];
    }
  }
  // The scratch solver is logically const here: it only reuses the trial's Schur factor.
  const_cast<ConstrainedSolver&>(solver_).solveHomogeneous3(step_.system, responses, 3 * first, onward ? 3 * first : 0);
}

void Rod::trialGeneralizedResponse(double* impulses) const {
  if (!trialValid_ || !solver_.ready()) {
    throw InvalidArgument("trial", "none", "solveTrial() must have succeeded on this rod since the last change");
  }
  const int n3 = 3 * controlPointCount();
  int firstRow = n3;
  for (int i = 0; i < n3; ++i) {
    if (!std::isfinite(impulses[i])) throw InvalidArgument("impulses", formatValue(impulses[i]), "must be finite");
    if (impulses[i] != 0.0 && firstRow == n3) firstRow = i;
  }
  if (firstRow == n3) return;  // no impulse, no response
  // The scratch solver is logically const here: it only reuses the trial's Schur factor.
  const_cast<ConstrainedSolver&>(solver_).solveHomogeneous(step_.system, impulses, firstRow);
}

void Rod::correctTrial(const double* dv) {
  if (!trialValid_) throw InvalidArgument("trial", "none", "solveTrial() must have succeeded since the last change");
  const int n = controlPointCount();
  for (int i = 0; i < n; ++i) {
    const size_t u = static_cast<size_t>(i);
    const Vec3 change(dv[3 * u], dv[3 * u + 1], dv[3 * u + 2]);
    step_.newVelocities[u] += change;
    step_.newPoints[u] += trialStep_ * change;
  }
}

void Rod::markInteraction(double s) {
  validateParameter(s);
  markedInteractions_.push_back(s);
}

void Rod::limitShapeChange(double s, double maxChange) {
  validateParameter(s);
  if (!(std::isfinite(maxChange) && maxChange >= 0.0))
    throw InvalidArgument("maxChange", formatValue(maxChange), "must be finite and >= 0");
  pendingShapeLimits_.push_back({s, maxChange});
}

StepReport Rod::commitTrial() {
  if (!trialValid_) throw InvalidArgument("trial", "none", "solveTrial() must have succeeded since the last change");
  StepReport report;
  if (!allFinite(step_.newPoints) || !allFinite(step_.newVelocities)) {
    // A correction (correctTrial) made the trial non-finite: keep the state, as for a failed solve.
    report.ok = false;
    report.failure = "the step produced a non-finite state";
    clearLoads();
    report.controlPoints = controlPointCount();
    return report;
  }
  interactions_.clear();
  for (const PointLoad& load : loads_) interactions_.push_back(load.parameter);
  for (const Spring& spring : springs_)
    if (spring.interaction) interactions_.push_back(spring.parameter);
  shapeLimits_.swap(pendingShapeLimits_);
  pendingShapeLimits_.clear();
  std::sort(shapeLimits_.begin(), shapeLimits_.end(),
            [](const ShapeLimit& a, const ShapeLimit& b) { return a.parameter < b.parameter; });
  interactions_.insert(interactions_.end(), markedInteractions_.begin(), markedInteractions_.end());
  contactLastStep_ = contactMarked_;
  contactMarked_ = false;
  // Free in this step: nothing but pins, clamps and point masses acted on it (they are added below).
  freeLastStep_ = interactions_.empty() && !contactLastStep_;
  recordInternalImpulse();  // before the swap: it needs the start-of-step forces and the new velocities
  points_.swap(step_.newPoints);
  velocities_.swap(step_.newVelocities);
  for (const Pin& p : pins_) interactions_.push_back(p.parameter);
  for (const auto& pointMass : pointMasses_) interactions_.push_back(pointMass.first);
  addClampNeighbours(interactions_);
  clearLoads();
  adapt(report);
  report.controlPoints = controlPointCount();
  return report;
}

double Rod::internalWeight(double h) const {
  if (settings_.timeIntegrator != TimeIntegrator::kBdf2 || historySteps_ == 0) return 1.0;
  // BDF2's coefficients assume equal steps; a changed h restarts it (relative change above 1e-12).
  if (!(std::abs(h - historyStep_) <= 1e-12 * h)) return 1.0;
  return 4.0 / 9.0;
}

void Rod::recordInternalImpulse() {
  if (settings_.timeIntegrator != TimeIntegrator::kBdf2) return;
  // g = c h (F_int - (h + beta) K v_new - eta K_m v_new) + H (method eq. 22c): the momentum the
  // internal forces gave this step, linearised as the step was, with the trial's final velocities
  // (corrections included).
  const int n = controlPointCount();
  const int local = degree() + 1;
  const size_t blocksPerSpan = static_cast<size_t>(local * (local + 1) / 2);
  const double h = trialStep_;
  const double c = trialInternalWeight_;
  const double scale = h + settings_.stiffnessDamping;
  const double eta = settings_.materialDamping;
  previousInternalImpulse_.swap(internalImpulse_);
  internalImpulse_.resize(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) internalImpulse_[static_cast<size_t>(i)] = (c * h) * step_.internalForce[static_cast<size_t>(i)];
  for (int j = 0; j < integrals_.spanCount(); ++j) {
    const Eigen::Matrix3d* k = &step_.stiffnessBlocks[static_cast<size_t>(j) * blocksPerSpan];
    const Eigen::Matrix3d* km = eta > 0.0 ? &step_.materialBlocks[static_cast<size_t>(j) * blocksPerSpan] : nullptr;
    const Vec3* v = &step_.newVelocities[static_cast<size_t>(j)];
    Vec3* g = &internalImpulse_[static_cast<size_t>(j)];
    for (int a = 0; a < local; ++a) {
      for (int b = 0; b <= a; ++b, ++k) {
        g[a] -= (c * h * scale) * (*k * v[b]);
        if (a != b) g[b] -= (c * h * scale) * (*k * v[a]);  // blocks are symmetric
        if (km != nullptr) {
          g[a] -= (c * h * eta) * (*km * v[b]);
          if (a != b) g[b] -= (c * h * eta) * (*km * v[a]);
          ++km;
        }
      }
    }
  }
  for (int i = 0; i < n; ++i) internalImpulse_[static_cast<size_t>(i)] += step_.historyTerm[static_cast<size_t>(i)];
  historySteps_ = c < 1.0 ? 2 : 1;
  historyStep_ = h;
}

double Rod::linearisationExcess() const {
  // The step solves the stretching force linearised about the start, f(x) ~ f0 - K0 (x - x0), i.e.
  // it moves on the quadratic model E0 - f0.dx + dx^T K0 dx / 2 of the stretching energy (eqs. 13-16),
  // dx = x1 - x0. Stretching is quartic in x: a rope that turns by theta in one step while straight
  // and taut lengthens by L theta^2 / 2, which the model does not see (its transverse stiffness is
  // the tension alone). What E(x1) holds beyond the model is energy the linearisation made. The
  // internal force and blocks stored by the pass include bending, which is quadratic in x (eq. 18)
  // and so enters the model exactly; it is taken out again here. O(n).
  const int d = degree();
  const int local = d + 1;
  const size_t blocksPerSpan = static_cast<size_t>(local * (local + 1) / 2);
  const double axial = settings_.axialStiffness();
  double energy = 0.0, work = 0.0, curvature = 0.0;
  Vec3 scratch[kMaxDegree + 1];
  for (int j = 0; j < integrals_.spanCount(); ++j) {
    const SpanView span = integrals_.span(j);
    const Vec3* q = &points_[static_cast<size_t>(j)];
    const Vec3* x = &step_.newPoints[static_cast<size_t>(j)];
    for (int a = 0; a < local; ++a) scratch[a] = Vec3::Zero();
    energy += stretchingSpan(span, x, axial, StiffnessMode::kClamped, scratch, nullptr);
    const Eigen::Matrix3d* k = &step_.stiffnessBlocks[static_cast<size_t>(j) * blocksPerSpan];
    for (int a = 0; a < local; ++a) {
      const Vec3 da = x[a] - q[a];
      // Bending's force on this span, -B (q - q_0) (as assembled), taken out of the internal force.
      Vec3 bendingForce = Vec3::Zero();
      for (int b = 0; b < local; ++b) bendingForce -= span.bending[a * local + b] * (q[b] - q[0]);
      work -= bendingForce.dot(da);
      for (int b = 0; b <= a; ++b, ++k) {
        const Vec3 db = x[b] - q[b];
        const double twice = a == b ? 1.0 : 2.0;
        curvature += twice * (da.dot(*k * db) - span.bending[a * local + b] * da.dot(db));
      }
    }
  }
  for (int i = 0; i < controlPointCount(); ++i) {
    const size_t u = static_cast<size_t>(i);
    work += step_.internalForce[u].dot(step_.newPoints[u] - points_[u]);
  }
  const double model = stretchingEnergy_ - work + 0.5 * curvature;
  return energy - model;
}

double Rod::trialEnergy() const {
  double sum = rope::stretchingEnergy(integrals_, step_.newPoints, settings_.axialStiffness()) +
               rope::bendingEnergy(integrals_, step_.newPoints);
  for (int j = 0; j < integrals_.spanCount(); ++j) {
    const SpanView span = integrals_.span(j);
    const Vec3* x = &step_.newPoints[static_cast<size_t>(j)];
    const Vec3* v = &step_.newVelocities[static_cast<size_t>(j)];
    for (int a = 0; a < span.localCount; ++a) {
      sum -= span.gravity[a] * settings_.gravity.dot(x[a]);
      for (int b = 0; b < span.localCount; ++b) sum += 0.5 * span.mass[a * span.localCount + b] * v[a].dot(v[b]);
    }
  }
  return sum;
}

bool Rod::needsRelinearisation(bool inContact) const {
  // Not while a body touches the rope (contact samples queued, addSpringSample) unless the caller
  // says the contact's active set is done (solveTrial's relineariseInContact): measured on a rope
  // wound ten times round a frictional drum (reliability_extremes_test), relinearised passes fed the
  // friction updates between passes and ran away (6.3 MJ within five substeps, from 278.5 J; a
  // frictionless drum kept its energy either way).
  if (!inContact) {
    for (const Spring& spring : springs_)
      if (!spring.interaction) return false;
  }
  return linearisationExcessive();
}

bool Rod::linearisationExcessive() const {
  // Corrected when the energy the linearisation made is more than 1 % of the energy in play: the
  // trial's kinetic energy, the start's stretching energy and m |g| L (and above 1e-12 EA L, strain
  // round-off). A rope of ordinary stiffness stays far below (the default 1 m rope released
  // horizontally: at most 1.2e-4 of m g L per step): its step is unchanged. A stiff thin rope (E = 1e13 Pa,
  // r = 0.5 mm) starting to swing at 1/60 s made 2.6e-4 J, 3 % of m g L, in its first step.
  if (step_.stiffnessBlocks.empty()) return false;
  const double excess = linearisationExcess();
  if (!(excess > 1e-12 * settings_.axialStiffness() * restLength())) return false;
  double kinetic = 0.0;
  for (int j = 0; j < integrals_.spanCount(); ++j) {
    const SpanView span = integrals_.span(j);
    const int local = span.localCount;
    const Vec3* v = &step_.newVelocities[static_cast<size_t>(j)];
    for (int a = 0; a < local; ++a)
      for (int b = 0; b < local; ++b) kinetic += 0.5 * span.mass[a * local + b] * v[a].dot(v[b]);
  }
  const double gravity = mass() * settings_.gravity.norm() * restLength();
  return excess > 0.01 * (kinetic + stretchingEnergy_ + gravity);
}

void Rod::assembleState(double h, const PointList* about) {
  const int n = controlPointCount();
  const int d = degree();
  const int local = d + 1;
  const double axial = settings_.axialStiffness();
  const double alpha = settings_.massDamping;
  const double beta = settings_.stiffnessDamping;
  const double c = internalWeight(h);
  const double eta = settings_.materialDamping;
  // M + h alpha M + c ((h^2 + h beta) K + h eta K_m) (method eq. 22a)
  const double massScale = 1.0 + h * alpha;
  const double stiffScale = c * (h * h + h * beta);
  const double dampScale = c * (h * eta);
  const Vec3 gravity = settings_.gravity;
  const size_t blocksPerSpan = static_cast<size_t>(local * (local + 1) / 2);

  step_.system.reset(n, 3, d);
  stretchingEnergy_ = 0.0;
  step_.force.assign(static_cast<size_t>(n), Vec3::Zero());
  step_.internalForce.assign(static_cast<size_t>(n), Vec3::Zero());
  step_.stiffnessTimesV.assign(static_cast<size_t>(n), Vec3::Zero());
  if (eta > 0.0) step_.materialTimesV.assign(static_cast<size_t>(n), Vec3::Zero());
  step_.massTimesV.assign(static_cast<size_t>(n), Vec3::Zero());
  step_.stiffnessBlocks.resize(static_cast<size_t>(integrals_.spanCount()) * blocksPerSpan);
  if (eta > 0.0) step_.materialBlocks.resize(step_.stiffnessBlocks.size());

  Eigen::Matrix3d blocks[(kMaxDegree + 1) * (kMaxDegree + 1)];
  Eigen::Matrix3d material[(kMaxDegree + 1) * (kMaxDegree + 1)];
  for (int j = 0; j < integrals_.spanCount(); ++j) {
    const SpanView span = integrals_.span(j);
    const Vec3* q = &points_[static_cast<size_t>(j)];
    const Vec3* v = &velocities_[static_cast<size_t>(j)];
    Vec3* f = &step_.force[static_cast<size_t>(j)];
    Vec3* kv = &step_.stiffnessTimesV[static_cast<size_t>(j)];
    Vec3* mv = &step_.massTimesV[static_cast<size_t>(j)];
    Vec3* mkv = eta > 0.0 ? &step_.materialTimesV[static_cast<size_t>(j)] : nullptr;
    Eigen::Matrix3d* stored = &step_.stiffnessBlocks[static_cast<size_t>(j) * blocksPerSpan];
    Eigen::Matrix3d* storedMaterial =
        eta > 0.0 ? &step_.materialBlocks[static_cast<size_t>(j) * blocksPerSpan] : nullptr;
    if (about == nullptr) {
      stretchingEnergy_ += stretchingSpan(span, q, axial, StiffnessMode::kClamped, f, blocks);
    } else {
      // Linearised about p = x1 instead: f(x) ~ f(p) - K(p) (x - p) = [f(p) + K(p) (p - x0)] - K(p) (x - x0),
      // the same form as the first pass with f0 -> f(p) + K(p) (p - x0), K0 -> K(p).
      const Vec3* p = &(*about)[static_cast<size_t>(j)];
      stretchingEnergy_ += stretchingSpan(span, p, axial, StiffnessMode::kClamped, f, blocks);
      for (int a = 0; a < local; ++a) {
        for (int b = 0; b <= a; ++b) {
          const Eigen::Matrix3d& k = blocks[a * local + b];
          f[a] += k * (p[b] - q[b]);
          if (a != b) f[b] += k.transpose() * (p[a] - q[a]);
        }
      }
    }
    if (eta > 0.0) {
      // The damping's strain rate at the step's midpoint, where it is the step's exact strain change
      // over h (stretching_energy.h): predicted from the start velocity, q + (h/2) v, in the first
      // pass and (q + p) / 2 once the end p is known. With the start's tangent a rope spinning at
      // omega sees omega h of its rigid rotation as strain rate each step (a 2 rad/s spin lost 13 % of
      // its angular momentum in 1 s at 1/240 s with eta = 10 ms, against 4.5 % undamped); with the
      // end's, a stiff rope turning by theta keeps the stretch the turn made (docs/method.md eq. 20).
      // A contact trial relinearised after the active set keeps the predicted midpoint: its first
      // trial p holds the stretch the correction removes (a rope sliding round a cylinder moved 95.0 %
      // of the Atwood travel with (q + p) / 2, 99.0 % with the predicted one; docs/method.md §8).
      Vec3 mid[kMaxDegree + 1];
      for (int a = 0; a < local; ++a) {
        mid[a] = about == nullptr || relinearisingInContact_
                     ? Vec3(q[a] + (0.5 * h) * v[a])
                     : Vec3(0.5 * (q[a] + (*about)[static_cast<size_t>(j + a)]));
      }
      materialStiffnessSpan(span, mid, axial, material);
    }
    for (int a = 0; a < local; ++a) {
      const Vec3 weight = span.gravity[a] * gravity;
      Vec3 fa = weight;
      for (int b = 0; b < local; ++b) fa -= span.bending[a * local + b] * (q[b] - q[0]);  // see bending_energy.cpp
      f[a] += fa;
      step_.internalForce[static_cast<size_t>(j + a)] -= weight;  // step_.force minus gravity, completed below
    }
    for (int a = 0; a < local; ++a) {
      for (int b = 0; b <= a; ++b) {
        Eigen::Matrix3d& k = blocks[a * local + b];
        k.diagonal().array() += span.bending[a * local + b];
        *stored++ = k;
        const double m = span.mass[a * local + b];
        kv[a] += k * v[b];
        mv[a] += m * v[b];
        if (a != b) {
          kv[b] += k * v[a];  // blocks are symmetric
          mv[b] += m * v[a];
        }
        Eigen::Matrix3d entry = stiffScale * k;
        if (eta > 0.0) {
          // Kelvin–Voigt damping eta K_m (eq. 20): the material stiffness, bending included.
          Eigen::Matrix3d& km = material[a * local + b];
          km.diagonal().array() += span.bending[a * local + b];
          *storedMaterial++ = km;
          mkv[a] += km * v[b];
          if (a != b) mkv[b] += km * v[a];
          entry += dampScale * km;
        }
        entry.diagonal().array() += massScale * m;
        step_.system.addBlock(j + a, j + b, entry);
      }
    }
  }

  // The internal (stretching and bending) forces: step_.force so far less gravity.
  for (int i = 0; i < n; ++i) step_.internalForce[static_cast<size_t>(i)] += step_.force[static_cast<size_t>(i)];

  BasisValues basis;
  // Point masses (method eq. 11a): m b_a b_b in the mass matrix, m g b_a in the gravity load.
  for (const auto& [s, m] : pointMasses_) {
    const int first = basisAt(knots_, s, basis);
    Vec3 u = Vec3::Zero();
    for (int a = 0; a < local; ++a) u += basis.d[0][static_cast<size_t>(a)] * velocities_[static_cast<size_t>(first + a)];
    for (int a = 0; a < local; ++a) {
      const double ba = basis.d[0][static_cast<size_t>(a)];
      step_.force[static_cast<size_t>(first + a)] += (m * ba) * gravity;
      step_.massTimesV[static_cast<size_t>(first + a)] += (m * ba) * u;
      for (int b = 0; b <= a; ++b) {
        step_.system.addBlock(first + a, first + b,
                         (massScale * m * ba * basis.d[0][static_cast<size_t>(b)]) * Eigen::Matrix3d::Identity());
      }
    }
  }
}

bool Rod::AssemblyCache::matches(const Rod& rod, double h, double c) const {
  const RodSettings& settings = rod.settings_;
  const auto same = [](const PointList& a, const PointList& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0);
  };
  return valid && integralsRevision == rod.integrals_.revision() && step == h && internalWeight == c &&
         axial == settings.axialStiffness() && massDamping == settings.massDamping &&
         stiffnessDamping == settings.stiffnessDamping && materialDamping == settings.materialDamping &&
         gravity == settings.gravity && pointMasses == rod.pointMasses_ && same(points, rod.points_) &&
         same(velocities, rod.velocities_);
}

void Rod::AssemblyCache::store(const Rod& rod, double h, double c) {
  const RodSettings& settings = rod.settings_;
  integralsRevision = rod.integrals_.revision();
  step = h;
  internalWeight = c;
  axial = settings.axialStiffness();
  massDamping = settings.massDamping;
  stiffnessDamping = settings.stiffnessDamping;
  materialDamping = settings.materialDamping;
  gravity = settings.gravity;
  pointMasses = rod.pointMasses_;
  points = rod.points_;
  velocities = rod.velocities_;
  system = rod.step_.system;
  force = rod.step_.force;
  valid = true;
}

bool Rod::assembleAndSolve(double h, StepReport& report, const PointList* about) {
  const int n = controlPointCount();
  const int d = degree();
  const int local = d + 1;
  const double alpha = settings_.massDamping;
  const double beta = settings_.stiffnessDamping;
  const double c = internalWeight(h);
  const double eta = settings_.materialDamping;

  // The rod's own part of the step (everything but loads and springs) depends only on its state: the
  // body-contact passes of a substep (solveTrial again with new contact springs) take it from the
  // last pass linearised about the start instead of assembling it again, bit for bit the same.
  if (about == nullptr && step_.assemblyCache.matches(*this, h, c)) {
    step_.system = step_.assemblyCache.system;
    step_.force = step_.assemblyCache.force;
  } else {
    step_.assemblyCache.valid = false;  // the members below are overwritten
    assembleState(h, about);
    if (about == nullptr) step_.assemblyCache.store(*this, h, c);
  }

  BasisValues basis;
  // Loads and springs mostly come in order along the rope (a contact's samples): each span search
  // starts from the last one's span (findSpanNear; findSpan, which throws, for a parameter outside).
  int hint = -1;
  const auto spanOf = [&](double s) {
    hint = knots_.contains(s) ? knots_.findSpanNear(s, hint) : knots_.findSpan(s);
    return hint;
  };

  for (const PointLoad& load : loads_) {
    const int k = spanOf(load.parameter);
    evaluateBasis(knots_, k, load.parameter, 0, basis);
    const Vec3 force = load.impulse ? Vec3(load.force / h) : load.force;
    for (int a = 0; a < local; ++a) step_.force[static_cast<size_t>(k - d + a)] += basis.d[0][static_cast<size_t>(a)] * force;
  }
  for (const Spring& spring : springs_) {
    const int k = spanOf(spring.parameter);
    const int order = spring.derivative;  // 0: on C(s), 1: on C'(s)
    evaluateBasis(knots_, k, spring.parameter, order, basis);
    const auto& b = basis.d[static_cast<size_t>(order)];
    const int first = k - d;
    Vec3 u = Vec3::Zero();
    for (int a = 0; a < local; ++a) u += b[static_cast<size_t>(a)] * velocities_[static_cast<size_t>(first + a)];
    const Vec3 force = spring.force - h * (spring.stiffness * u);
    const Eigen::Matrix3d matrix = h * h * spring.stiffness + h * spring.damping;
    for (int a = 0; a < local; ++a) {
      const double ba = b[static_cast<size_t>(a)];
      step_.force[static_cast<size_t>(first + a)] += ba * force;
      for (int c = 0; c <= a; ++c) step_.system.addBlock(first + a, first + c, (ba * b[static_cast<size_t>(c)]) * matrix);
    }
  }

  // BDF2's history term H = (6 g_n - g_{n-1}) / 9 (method eq. 22c), zero on a restart step.
  step_.historyTerm.assign(static_cast<size_t>(n), Vec3::Zero());
  if (c < 1.0) {
    for (int i = 0; i < n; ++i) {
      const size_t u = static_cast<size_t>(i);
      step_.historyTerm[u] = (6.0 * internalImpulse_[u] - (historySteps_ > 1 ? previousInternalImpulse_[u] : Vec3::Zero())) / 9.0;
    }
  }
  trialInternalWeight_ = c;
  step_.rhs.resize(static_cast<size_t>(3 * n));
  for (int i = 0; i < n; ++i) {
    const size_t u = static_cast<size_t>(i);
    // Backward Euler (and BDF2's restart step) in the one expression of eq. 22, so that its rounding
    // does not depend on the integrator chosen; BDF2 reweights the internal part (eq. 22a).
    Vec3 damped = (beta + h) * step_.stiffnessTimesV[u];
    if (eta > 0.0) damped += eta * step_.materialTimesV[u];
    const Vec3 r = c == 1.0 ? Vec3(h * (step_.force[u] - alpha * step_.massTimesV[u] - damped))
                            : Vec3(h * (step_.force[u] - step_.internalForce[u] - alpha * step_.massTimesV[u]) +
                                   (c * h) * (step_.internalForce[u] - damped) + step_.historyTerm[u]);
    for (int axis = 0; axis < 3; ++axis) step_.rhs[static_cast<size_t>(3 * i + axis)] = r[axis];
  }
  if (!step_.system.factorize()) {
    report.ok = false;
    report.failure = "factorisation failed: the step matrix is not positive definite or not finite";
    return false;
  }

  // Pins and clamps: three position rows each, two tangent rows more per clamp (pin_constraints.h).
  rows_.clear();
  for (const Pin& pinned : pins_) {
    rows_.push_back(pinRows(knots_, points_, velocities_, pinned.parameter, pinned.target, h));
    if (pinned.isClamp()) {
      rows_.push_back(clampTangentRows(knots_, points_, velocities_, pinned.parameter, pinned.direction, h));
    }
  }
  if (!solver_.solve(step_.system, rows_, step_.rhs.data())) {
    report.ok = false;
    report.failure = "pin or clamp constraints are dependent or not finite";
    return false;
  }

  step_.newPoints.resize(static_cast<size_t>(n));
  step_.newVelocities.resize(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const size_t u = static_cast<size_t>(i);
    const Vec3 dv(step_.rhs[3 * u], step_.rhs[3 * u + 1], step_.rhs[3 * u + 2]);
    step_.newVelocities[u] = velocities_[u] + dv;
    step_.newPoints[u] = points_[u] + h * step_.newVelocities[u];
  }
  if (!allFinite(step_.newPoints) || !allFinite(step_.newVelocities)) {
    report.ok = false;
    report.failure = "the step produced a non-finite state";
    return false;
  }
  if (overstretchedBy(step_.newPoints)) {
    report.ok = false;
    report.failure = "the step stretched the rope past Rod::kMaxStepStretch times its rest length";
    return false;
  }
  // P C'(s) = 0 also admits a tangent pointing against the clamp's direction (the rope folded back
  // on itself at s within the step): a failed step, not a silently reversed weld.
  for (const Pin& pinned : pins_) {
    if (!pinned.isClamp()) continue;
    const Vec3 tangent = evaluateCurve(knots_, step_.newPoints, pinned.parameter).firstDerivative;
    if (!(tangent.dot(pinned.direction) > 0.0)) {
      report.ok = false;
      report.failure = "a clamp's tangent reversed within the step";
      return false;
    }
  }
  return true;
}

void Rod::swapStepScratch(StepScratch& scratch) {
  if (trialValid_) {
    throw InvalidArgument("trial", "pending", "swapStepScratch needs a rod with no trial (before solveTrial or after commitTrial)");
  }
  // The queued springs move into the lent buffer (usually there are none between steps).
  scratch.springs.assign(springs_.begin(), springs_.end());
  springs_.swap(scratch.springs);
  scratch.springs.clear();
  // Another rod's assembly never matches this rod's inputs: the integrals' revision in its key is
  // process-wide (rod_integrals.h), shared only by a copy, whose assembly is then this rod's own.
  std::swap(step_, scratch.buffers);
}

void Rod::prefetch() const {
  prefetchState();
  step_.system.prefetch();
  prefetchVector(step_.rhs);
  prefetchVector(step_.force);
  prefetchVector(step_.stiffnessTimesV);
  prefetchVector(step_.materialTimesV);
  prefetchVector(step_.massTimesV);
  prefetchVector(step_.internalForce);
  prefetchVector(step_.historyTerm);
  prefetchVector(step_.stiffnessBlocks);
  prefetchVector(step_.materialBlocks);
  prefetchVector(step_.newPoints);
  prefetchVector(step_.newVelocities);
  prefetchVector(step_.relinearisationPoints);
}

void Rod::prefetchState() const {
  prefetchVector(knots_.values());
  prefetchVector(points_);
  prefetchVector(velocities_);
  prefetchVector(rest_);
  integrals_.prefetch();
  prefetchVector(pins_);
  prefetchVector(loads_);
  prefetchVector(springs_);
  prefetchVector(rows_);
  prefetchVector(shapeLimits_);
  prefetchVector(internalImpulse_);
  prefetchVector(previousInternalImpulse_);
  prefetchVector(bend_);
  prefetchVector(spans_);
}

}  // namespace rope
