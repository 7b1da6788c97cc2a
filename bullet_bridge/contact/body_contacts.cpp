// SPDX-License-Identifier: MIT
#include "bullet_bridge/contact/body_contacts.h"

#include <BulletCollision/BroadphaseCollision/btBroadphaseProxy.h>
#include <LinearMath/btAabbUtil2.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/LU>

#include "bullet_bridge/detail/body_state.h"
#include "bullet_bridge/detail/bullet_math.h"
#include "bullet_bridge/find_contacts.h"
#include "rope/common/error.h"
#include "rope/common/prefetch.h"
#include "rope/spline/bspline_basis.h"
#include "rope/spline/bspline_curve.h"

namespace rope::bullet {

namespace {

// A world point in the frame of `frame`, computed componentwise: Bullet's SIMD inverse multiplies
// unused vector lanes, which raised FE_INVALID under FP traps in the float build.
btVector3 toLocal(const btTransform& frame, const Vec3& point) {
  const btVector3 offset = toBullet(point) - frame.getOrigin();
  const btMatrix3x3& basis = frame.getBasis();
  btVector3 local(0, 0, 0);  // all four lanes set: the float build warns of the unused fourth (-Werror)
  for (int i = 0; i < 3; ++i)
    local[i] = basis[0][i] * offset.x() + basis[1][i] * offset.y() + basis[2][i] * offset.z();
  return local;
}

Vec3 tangential(const Vec3& v, const Vec3& normal) { return v - normal * normal.dot(v); }

// Relative tolerance on mu f_n before a sticking sample is switched to sliding: round-off of the
// end-of-step force must not flip samples that sit exactly on the friction cone.
constexpr double kConeTolerance = 1e-6;
// A sliding sample's friction bound is re-estimated when its end-of-step normal force differs by more.
constexpr double kNormalForceTolerance = 0.05;
// GMRES on the sliding bounds (solveSlidingBounds): products at most (12-17 measured round a drum,
// two turns at mu = 1) and the relative residual it stops at; unconverged, the passes re-bound.
constexpr int kBoundIterations = 60;
constexpr double kBoundTolerance = 1e-10;
// Size of the bounds' coupling M (solveSlidingBounds: |M 1|_inf, its row-sum norm where rows share a
// sign) above which they are solved exactly; below it, the error of the pass-by-pass re-bound shrinks
// by at least this factor per pass.
constexpr double kStrongBoundCoupling = 0.5;
// Probe step of the surface's curvature along the rope, rope radii: short against every curvature
// radius a rope can follow (at least its own radius, at an edge), long against the narrowphase's
// 1e-12 relative accuracy.
constexpr double kCurvatureProbe = 0.1;
// The turning normal's negative stiffness (springOf) is capped at this share of the sample's own
// mass over h^2, so the step's matrix stays positive definite whatever the pressure; a rope wrapped
// round a support needs p kappa = T kappa^2 (0.63 of it for 10 N round a 5.5 cm radius at 1/240 s,
// 5 mm nylon).
constexpr double kGeometricShare = 0.9;
// The sliding corrections of the normal law (springOf) take at most this share of the penetration
// force: beyond it the rope leaves the surface within the step (fast over an edge), which the next
// substep's gap measures.
constexpr double kOpeningShare = 0.5;
// A sample whose friction force is at least this share of mu f_n holds a load by friction (a rope
// round a drum: 0.97 on average at 0.9 of the capstan limit for mu theta = pi). Below it, the sample
// only rests (a rope on a floor, or one that has just touched: ~0 of f_n).
constexpr double kHeldFrictionShare = 0.5;
// Share of a friction-holding sample's normal force that a knot removal may change it by.
constexpr double kRemovalForceShare = 0.1;
// A gap this small is contact to rounding (m): coordinates of a few metres carry ~1e-16 m of it.
constexpr double kTouchingDistance = 1e-12;

}  // namespace

namespace {
const char* const kFrictionCombiner = "friction combiner";
}  // namespace

void BodyContacts::reset() {
  samples_.clear();
  anchors_.clear();
}

void BodyContacts::gather(const Rod& rod, const CapsuleProxies& proxies,
                          const std::vector<const btCollisionObject*>& candidates, const BulletRopeSettings& settings,
                          const Exclusion& excluded, const FrictionOf& friction, double h,
                          std::vector<RopeContactRecord>& records, RopeStepRecord& step) {
  samples_.clear();
  for (const btCollisionObject* object : candidates) {
    if (!isFinite(object->getWorldTransform())) {
      ++step.skippedBodies;  // a NaN body must not poison the rope
      continue;
    }
    if (object->getBroadphaseHandle() == nullptr) continue;
    const std::size_t first = samples_.size();
    try {
      gatherBody(rod, proxies, *object, settings, excluded, friction, h, step);
    } catch (const InvalidArgument& error) {
      if (error.parameter() == kFrictionCombiner) throw;  // the user's combiner: fails the substep
      samples_.resize(first);
      ++step.skippedBodies;  // a shape the narrowphase does not support
    }
  }

  for (Sample& sample : samples_) {
    const Contact& contact = sample.geometry.contact;
    const double distance = static_cast<double>(contact.distance);
    RopeContactRecord record;
    record.body = sample.object;
    record.s = sample.geometry.s;
    record.point = contact.pointOnBody;
    record.normal = contact.normal;
    record.depth = -distance;
    step.maxPenetration = std::max(step.maxPenetration, -distance);
    sample.active = contactActive(distance, sample.normal, sample.ropeVelocity, sample.bodyVelocity, h);
    if (sample.active) {
      sample.spring = springOf(sample, h);
      ++step.contacts;
    }
    record.active = sample.active;
    sample.record = static_cast<int>(records.size());
    records.push_back(record);
  }
}

void BodyContacts::gatherBody(const Rod& rod, const CapsuleProxies& proxies, const btCollisionObject& object,
                              const BulletRopeSettings& settings, const Exclusion& excluded,
                              const FrictionOf& friction, double h, RopeStepRecord& step) {
  const btBroadphaseProxy* handle = object.getBroadphaseHandle();
  const double margin = settings.speculativeMargin;
  const double radius = rod.settings().radius;
  // How far the body's surface can move in the step: linear speed plus spin times its box's reach.
  const double bodyReach = sweptReach(object, h);
  if (!std::isfinite(bodyReach)) {
    ++step.skippedBodies;
    return;
  }
  btRigidBody* body = dynamicBody(object);
  const std::size_t first = samples_.size();
  // Midphase: the capsules whose tree leaves (swept boxes, capsule_proxies.h) meet the body's box
  // grown by its reach, in capsule order.
  const btScalar grow = static_cast<btScalar>(bodyReach);
  const btVector3 bodyGrow(grow, grow, grow);
  proxies.capsulesOverlapping(handle->m_aabbMin - bodyGrow, handle->m_aabbMax + bodyGrow, nearCapsules_, treeStack_);
  const std::vector<double>* speeds = nearCapsules_.empty() ? nullptr : &proxies.endSpeeds(rod);
  int spanHint = -1;
  for (const int i : nearCapsules_) {
    const Capsule capsule = proxies.capsule(i);
    const CapsuleProxy& proxy = proxies.proxy(i);
    // Speculative distance: the configured margin plus what rope and body can close in this step,
    // so a fast rope meets a thin plate before it has passed it.
    const double ropeReach = h * std::max((*speeds)[static_cast<std::size_t>(i)], (*speeds)[static_cast<std::size_t>(i) + 1]);
    const double reach = margin + ropeReach + bodyReach;
    const btScalar grow = static_cast<btScalar>(radius + reach);
    btVector3 lo = capsule.a, hi = capsule.a;
    lo.setMin(capsule.b);
    hi.setMax(capsule.b);
    lo -= btVector3(grow, grow, grow);
    hi += btVector3(grow, grow, grow);
    if (!TestAabbAgainstAabb2(lo, hi, handle->m_aabbMin, handle->m_aabbMax)) continue;
    if (excluded(object, proxy.s0, proxy.s1)) continue;
    chordContacts_.clear();
    findContacts(capsule, object, reach, chordContacts_);
    if (chordContacts_.empty()) continue;
    const Contact* nearest = &chordContacts_.front();
    for (const Contact& c : chordContacts_)
      if (c.distance < nearest->distance) nearest = &c;
    scratch_.clear();
    sampler_.sampleCapsule(rod, i, proxy.s0, proxy.s1, capsule, object, reach, *nearest,
                           settings.contactQuadraturePoints, scratch_);
    for (const ContactSample& geometry : scratch_) {
      Sample sample;
      sample.geometry = geometry;
      sample.object = &object;
      sample.body = body;
      sample.normal = toVec(geometry.contact.normal);
      const KnotVector& knots = rod.knots();
      // Samples come in order along the rope: the span search starts from the last sample's span.
      const int span = knots.findSpanNear(geometry.s, spanHint);
      spanHint = span;
      BasisValues basis;
      evaluateBasis(knots, span, geometry.s, 0, basis);
      sample.first = span - knots.degree();
      sample.count = knots.degree() + 1;
      for (int a = 0; a < sample.count; ++a) sample.basis[a] = basis.d[0][static_cast<std::size_t>(a)];
      sample.ropeVelocity = curveAt(sample, rod.velocities());
      // rod.position(s) and rod.tangent(s), bitwise, from the span just found (no search).
      const auto position = [&] {
        int hint = span;
        return curvePositionNear(knots, rod.controlPoints(), geometry.s, hint);
      };
      int derivativeSpan = span;
      const Vec3 derivative = evaluateCurveNear(knots, rod.controlPoints(), geometry.s, derivativeSpan).firstDerivative;
      const double derivativeNorm = derivative.norm();
      const Vec3 tangent = derivativeNorm > 0.0 ? Vec3(derivative / derivativeNorm) : Vec3(Vec3::Zero());
      sample.bodyVelocity = pointVelocity(object, geometry.contact.pointOnBody, geometry.contact.childIndex);
      // Friction state: the stored anchor (interpolated along the curve), or a new one here.
      const Vec3 slip = tangential(sample.ropeVelocity - sample.bodyVelocity, sample.normal);
      btVector3 anchor;
      bool sliding = false;
      double pressure = -1.0;
      const bool stored = anchors_.find(object, geometry.s, proxy.s1 - proxy.s0, rod, anchor, sliding, pressure);
      sample.pressureEstimate = pressure;
      if (!stored) sliding = slip.norm() >= settings.frictionVelocity;
      if (sliding && slip.norm() >= settings.frictionVelocity) {
        sample.friction.sliding = true;
        sample.friction.direction = slip.normalized();
        sample.friction.speed = slip.norm();
      } else if (stored) {
        sample.friction.displacement = tangential(position() - toVec(anchor), sample.normal);
      }
      // The surface's curvature along the rope, for a rope that slides along itself (springOf; at
      // rest it changes nothing, and a resting rope costs no probe): the turn of the normal over a
      // probe step of kCurvatureProbe rope radii along the rope's tangent, one more ball query.
      const Vec3 along = tangential(tangent, sample.normal);
      if (along.norm() > 0.5 && std::abs(along.dot(slip)) >= settings.frictionVelocity * along.norm()) {
        sample.along = along.normalized();
        const double step = kCurvatureProbe * radius;
        if (sampler_.ballContact(toBullet(position() + step * sample.along), capsule.radius, object,
                                 reach + step, probe_))
          sample.curvature = sample.along.dot(toVec(probe_.normal) - sample.normal) / step;
      }
      samples_.push_back(sample);
    }
  }

  // The laws: the line law times each sample's weight, capped in sum on a dynamic body.
  double stiffnessScale = 1.0, dampingScale = 1.0, speculativeScale = 1.0;
  double frictionDampingLimit = std::numeric_limits<double>::max();
  if (body != nullptr && samples_.size() > first) {
    double inverseMass = 0.0, weight = 0.0;
    for (std::size_t i = first; i < samples_.size(); ++i) {
      const Contact& c = samples_[i].geometry.contact;
      inverseMass = std::max(inverseMass, static_cast<double>(body->computeImpulseDenominator(c.pointOnBody, c.normal)));
      weight += samples_[i].geometry.weight;
    }
    if (inverseMass > 0.0) {
      const double mass = 1.0 / inverseMass, share = settings.bodyStabilityFactor;
      stiffnessScale = std::min(1.0, share * mass / (h * h * settings.lineContactStiffness * weight));
      dampingScale = std::min(1.0, share * mass / (h * settings.lineContactDamping * weight + 1e-300));
      speculativeScale = std::min(1.0, share * mass / (h * settings.lineSpeculativeDamping * weight + 1e-300));
      frictionDampingLimit = share * mass / (h * static_cast<double>(samples_.size() - first));
    }
  }
  // The pair's coefficient (friction_combination.h), once per body touched.
  const double mu = samples_.size() > first ? friction(object) : 0.0;
  if (!(std::isfinite(mu) && mu >= 0.0)) {
    throw InvalidArgument(kFrictionCombiner, formatValue(mu), "must return a finite value >= 0");
  }
  for (std::size_t i = first; i < samples_.size(); ++i) {
    Sample& sample = samples_[i];
    const double w = sample.geometry.weight;
    sample.law.stiffness = settings.lineContactStiffness * w * stiffnessScale;
    sample.law.damping = settings.lineContactDamping * w * dampingScale;
    sample.law.speculativeDamping = settings.lineSpeculativeDamping * w * speculativeScale;
    sample.law.friction = mu;
    sample.law.frictionVelocity = settings.frictionVelocity;
    sample.law.frictionDampingLimit = frictionDampingLimit;
    sample.geometricLimit = kGeometricShare * rod.settings().effectiveLinearDensity() * w / (h * h);
    // Until a solve says otherwise, sliding friction is bounded by the pressure the sample's stretch
    // ended the last substep with, or else by the penetration force.
    sample.friction.normalForce =
        sample.pressureEstimate >= 0.0
            ? sample.pressureEstimate * w
            : std::max(0.0, -sample.law.stiffness * static_cast<double>(sample.geometry.contact.distance));
  }
}

bool BodyContacts::pushesBodies() const {
  for (const Sample& sample : samples_) {
    if (sample.body != nullptr) return true;
  }
  return false;
}

void BodyContacts::prefetch() const {
  prefetchVector(samples_);  // as many as last substep: a rope at rest finds the same again
  anchors_.prefetch();
}

void BodyContacts::queue(Rod& rod) const {
  for (const Sample& sample : samples_) {
    if (!sample.active) continue;
    rod.addSpringSample(sample.geometry.s, sample.spring.force, sample.spring.stiffness, sample.spring.damping);
  }
}

ContactSpring BodyContacts::springOf(const Sample& sample, double h) {
  const double distance = static_cast<double>(sample.geometry.contact.distance);
  ContactSpring spring = sampleSpring(sample.law, distance, sample.normal, sample.ropeVelocity, sample.bodyVelocity, h,
                                      sample.friction);
  const double pressing = -sample.law.stiffness * distance;  // N, the penetration force
  if (!(pressing > 0.0) || sample.curvature == 0.0) return spring;
  // A rope sliding over a curved surface (docs/method.md §11, eq. 32): its point moves by
  // delta = h (u_new - v_b) along the surface, over which the normal turns by kappa delta_t and the gap
  // opens by kappa delta_t^2 / 2 (delta_t = along . delta, kappa the curvature along the rope). The law
  // linearised at the start of the step (eqs. 31-32) sees neither: its force ends along the old
  // normal, which has a component -f_n kappa delta_t against the slide, and its gap and approach
  // speed make the rope sit deeper by kappa delta_t^2 / 2. Round a support this was a viscous drag
  // of f_n kappa h per unit speed: T theta kappa h v in all, a frictionless rope over a 5 cm cylinder
  // loaded 1.1 : 1 moved 69 % as far as the Atwood machine it is (issue 13).
  //  * the turning normal, f += f_n kappa delta_t along: a negative stiffness -f_n kappa along along^T
  //    in the implicit step (the rope's own tension's geometric stiffness T kappa^2 balances it), with
  //    the body's motion taken out of delta (f0 += -h f_n kappa (along . v_b) along);
  //  * the gap's opening and the turning normal's share of n . w, explicit from the slide at the start
  //    of the step: f_n -= k kappa (h w_t)^2 / 2 + c kappa h w_t^2.
  const double kappa = sample.curvature;
  const double slide = sample.along.dot(sample.ropeVelocity - sample.bodyVelocity);  // m/s
  const double opening = kappa * slide * slide * h * (0.5 * sample.law.stiffness * h + sample.law.damping);  // N
  spring.force -= std::clamp(opening, -kOpeningShare * pressing, kOpeningShare * pressing) * sample.normal;
  const double turning = std::min(pressing * kappa, sample.geometricLimit);  // N/m
  spring.stiffness -= turning * sample.along * sample.along.transpose();
  spring.force -= h * turning * sample.along.dot(sample.bodyVelocity) * sample.along;
  return spring;
}

btVector3 BodyContacts::bodyPointAfter(const Sample& sample, const Vec3& slip, double radius, double h) {
  // The rope's point slid by delta = h P_t slip along the surface; the body point under it moved by
  // delta less rho kappa (along . delta) along (rho = radius + gap, from the rope's centre line to the
  // surface): R / (R + rho) of it round a cylinder of radius R, none of it across an edge. The turned
  // normal force (springOf) applied there has no moment about a round body's axis, as the true force
  // has none.
  const Contact& contact = sample.geometry.contact;
  if (sample.curvature == 0.0) return contact.pointOnBody;
  const Vec3 delta = h * tangential(slip, sample.normal);
  const double rho = radius + static_cast<double>(contact.distance);
  return contact.pointOnBody + toBullet(delta - rho * sample.curvature * sample.along.dot(delta) * sample.along);
}

bool BodyContacts::solveSlidingBounds(Rod& rod, double h) {
  // A sliding sample i pulls the rope with -mu_i f_i d_i, the bound f_i fixed in the trial. The normal
  // force each sample ends the step with is affine in the trial (endOfStepForce):
  //   N_j = N_j^trial + g_j . du(s_j),   g_j = -(h K_j + D_j)^T n_j,
  // and changing the bounds by delta changes the generalised impulses by
  //   J(delta) = sum_i -mu_i h delta_i b(s_i) d_i,   so   du = R J(delta)
  // with R the trial's factorised step, pins held (Rod::trialGeneralizedResponse). Coulomb's law wants
  // f = N(f), i.e. with f = f^used + delta (docs/method.md §11, active set):
  //   (I - M) delta = N^trial - f^used,   (M delta)_j = g_j . (R J(delta))(s_j).
  // Iterating f instead (one trial per pass with the last pass's N) multiplies the error by M, which
  // round a support behaves like the capstan's own Volterra operator mu theta: the passes diverged for
  // mu theta >= pi and a rope that should hold at 0.9 exp(mu theta) slid. GMRES (rope/common/gmres.h)
  // solves it with one rod solve per product and never forms M: a rope wound twice round a drum at
  // mu = 1 has about 370 sliding samples, which GMRES resolves to 1e-10 in 12-17 products. Forming M
  // takes one rod solve per sample and an O(m^3) factorisation: the two-turn capstan slip test ran
  // 5.9 s that way, 0.9 s with GMRES (same figures), and the knot and pile steps are not slower.
  sliding_.clear();
  if (!exactBounds_) return false;
  for (std::size_t i = 0; i < samples_.size(); ++i) {
    const Sample& sample = samples_[i];
    if (!(sample.active && sample.friction.sliding && sample.law.friction > 0.0)) continue;
    // On a moving body (a spinning drum) the exact bounds threw a rope wound ten turns round it at
    // 150 m/s, pass-by-pass ones do not (reliability_extremes_test); not understood yet, so moving
    // bodies keep the pass-by-pass bounds.
    if (sample.bodyVelocity.squaredNorm() > 0.0) return false;
    sliding_.push_back(static_cast<int>(i));
  }
  const int m = static_cast<int>(sliding_.size());
  if (m == 0) return false;
  gatherSlidingTerms(rod, h);
  // Weak coupling (a rope on a flat floor, a heap on the ground: friction barely moves the normal
  // forces) is left to the pass-by-pass re-bound, which converges there and keeps a resting rope's
  // friction from following every flicker of its normal forces (solving it too made the 2 m pile's
  // resting jitter 6 mm/s instead of 3). |M 1|_inf stands in for M's row-sum norm: a lower bound of
  // it, equal where a row's entries share a sign, as round a support, where raising any bound raises
  // the tension and with it every normal force.
  boundDelta_.assign(static_cast<std::size_t>(m), 1.0);
  respondToBoundChange(rod, boundDelta_.data());
  double coupling = 0.0;
  for (int j = 0; j < m; ++j) coupling = std::max(coupling, std::abs(normalForceChange(j)));
  if (coupling < kStrongBoundCoupling) return false;
  const GmresResult solved = gmres_.solve(
      m,
      [&](const double* delta, double* product) {
        respondToBoundChange(rod, delta);
        for (int j = 0; j < m; ++j) product[j] = delta[j] - normalForceChange(j);
      },
      boundRhs_.data(), boundDelta_.data(), GmresSettings{kBoundIterations, kBoundTolerance});
  if (!solved.converged) return false;  // the trial is unchanged; the passes re-bound instead
  // A negative bound is a sample that lifts off: bounded by zero here, released by update().
  for (int i = 0; i < m; ++i) {
    Sample& sample = samples_[static_cast<std::size_t>(sliding_[static_cast<std::size_t>(i)])];
    const std::size_t u = static_cast<std::size_t>(i);
    const double bound = std::max(0.0, sample.friction.normalForce + boundDelta_[u]);
    boundDelta_[u] = bound - sample.friction.normalForce;
    sample.friction.normalForce = bound;
    sample.spring = springOf(sample, h);
  }
  respondToBoundChange(rod, boundDelta_.data());
  rod.correctTrial(correction_.data());
  return true;
}

void BodyContacts::gatherSlidingTerms(const Rod& rod, double h) {
  const KnotVector& knots = rod.knots();
  const std::size_t m = sliding_.size();
  const std::size_t width = static_cast<std::size_t>(knots.degree() + 1);
  slidingFirst_.resize(m);
  slidingBasis_.resize(m * width);
  slidingPull_.resize(m);
  slidingGradient_.resize(m);
  boundRhs_.resize(m);
  for (std::size_t j = 0; j < m; ++j) {
    const Sample& sample = samples_[static_cast<std::size_t>(sliding_[j])];
    slidingFirst_[j] = sample.first;
    for (std::size_t a = 0; a < width; ++a) slidingBasis_[j * width + a] = sample.basis[a];
    slidingPull_[j] = -sample.law.friction * h * sample.friction.direction;
    slidingGradient_[j] = -(h * sample.spring.stiffness + sample.spring.damping).transpose() * sample.normal;
    const Vec3 force = endOfStepForce(sample.spring, sample.ropeVelocity, curveAt(sample, rod.trialVelocities()), h);
    boundRhs_[j] = force.dot(sample.normal) - sample.friction.normalForce;
  }
  correction_.resize(static_cast<std::size_t>(3 * rod.controlPointCount()));
}

void BodyContacts::respondToBoundChange(const Rod& rod, const double* delta) {
  const std::size_t width = slidingBasis_.size() / std::max<std::size_t>(1, sliding_.size());
  std::fill(correction_.begin(), correction_.end(), 0.0);
  for (std::size_t i = 0; i < sliding_.size(); ++i) {
    const Vec3 impulse = delta[i] * slidingPull_[i];
    double* point = &correction_[3 * static_cast<std::size_t>(slidingFirst_[i])];
    for (std::size_t a = 0; a < width; ++a, point += 3) {
      const double b = slidingBasis_[i * width + a];
      point[0] += b * impulse.x();
      point[1] += b * impulse.y();
      point[2] += b * impulse.z();
    }
  }
  rod.trialGeneralizedResponse(correction_.data());
}

double BodyContacts::normalForceChange(int j) const {
  const std::size_t u = static_cast<std::size_t>(j);
  const std::size_t width = slidingBasis_.size() / sliding_.size();
  const double* point = &correction_[3 * static_cast<std::size_t>(slidingFirst_[u])];
  Vec3 velocity = Vec3::Zero();
  for (std::size_t a = 0; a < width; ++a, point += 3)
    velocity += slidingBasis_[u * width + a] * Vec3(point[0], point[1], point[2]);
  return slidingGradient_[u].dot(velocity);
}

Vec3 BodyContacts::curveAt(const Sample& sample, const PointList& field) {
  const Vec3* q = field.data() + sample.first;
  Vec3 value = Vec3::Zero();
  for (int a = 0; a < sample.count; ++a) value += sample.basis[a] * q[a];
  return value;
}

BodyContacts::Change BodyContacts::changeFor(const Sample& sample, const Rod& rod, double h, Vec3& uNew,
                                             double& normalForce, Vec3& tangentForce) {
  uNew = curveAt(sample, rod.trialVelocities());
  const Vec3 force = endOfStepForce(sample.spring, sample.ropeVelocity, uNew, h);
  normalForce = force.dot(sample.normal);
  if (normalForce < 0.0) return Change::kRelease;  // pulls the rope onto the body
  const double mu = sample.law.friction;
  if (!(mu > 0.0)) return Change::kNone;
  const SampleFriction& friction = sample.friction;
  if (!friction.sliding) {
    tangentForce = tangential(force, sample.normal);
    // The spring would need more than mu f_n: the sample slides.
    return tangentForce.norm() <= mu * normalForce * (1.0 + kConeTolerance) ? Change::kNone : Change::kSlide;
  }
  return std::abs(normalForce - friction.normalForce) > kNormalForceTolerance * std::max(normalForce, friction.normalForce)
             ? Change::kRebound
             : Change::kNone;
}

bool BodyContacts::update(Rod& rod, double h, std::vector<RopeContactRecord>& records, RopeStepRecord& step) {
  solveSlidingBounds(rod, h);
  bool changed = false;
  for (Sample& sample : samples_) {
    if (!sample.active) continue;
    Vec3 uNew, tangentForce;
    double normalForce = 0.0;
    const Change change = changeFor(sample, rod, h, uNew, normalForce, tangentForce);
    if (change == Change::kNone) continue;
    changed = true;
    if (change == Change::kRelease) {
      sample.active = false;  // released for the rest of the substep
      records[static_cast<std::size_t>(sample.record)].active = false;
      --step.contacts;
      continue;
    }
    SampleFriction& friction = sample.friction;
    if (change == Change::kSlide) {  // along the way the force pushes it
      friction.sliding = true;
      friction.direction = -tangentForce / tangentForce.norm();
      friction.speed = std::max(tangential(uNew - sample.bodyVelocity, sample.normal).norm(), sample.law.frictionVelocity);
    }
    friction.normalForce = normalForce;
    sample.spring = springOf(sample, h);
  }
  return changed;
}

bool BodyContacts::settled(const Rod& rod, double h) const {
  for (const Sample& sample : samples_) {
    if (!sample.active) continue;
    Vec3 uNew, tangentForce;
    double normalForce = 0.0;
    if (changeFor(sample, rod, h, uNew, normalForce, tangentForce) != Change::kNone) return false;
  }
  return true;
}

void BodyContacts::finish(Rod& rod, double h, double concentratedContactRatio,
                          std::vector<RopeContactRecord>& records) {
  for (const Sample& sample : samples_) {
    if (!sample.active) continue;
    const double s = sample.geometry.s;
    const Vec3 uNew = curveAt(sample, rod.trialVelocities());
    const Vec3 force = endOfStepForce(sample.spring, sample.ropeVelocity, uNew, h);
    const btVector3 point = bodyPointAfter(sample, uNew - sample.bodyVelocity, rod.settings().radius, h);
    RopeContactRecord& record = records[static_cast<std::size_t>(sample.record)];
    record.force = toBullet(force);
    record.sticking = !sample.friction.sliding;
    if (sample.body != nullptr) {
      // Newton's third law: the body gets exactly the opposite of what the rope felt over the step.
      sample.body->applyImpulse(toBullet(-force * h), point - sample.body->getCenterOfMassPosition());
      sample.body->activate();
    }
    if (!(sample.law.friction > 0.0)) continue;
    limitShapeChangeWhereFrictionHolds(rod, s, force, sample);
    // The anchor for the next substep, where the body will be after its next integration.
    const Vec3 xNew = rod.position(s) + h * uNew;
    const Vec3 bodyMotion = h * sample.bodyVelocity;
    // Sliding: an anchor that puts the spring at the friction force the sample ends the step with
    // (x - a = -f_t / k), so a sample that sticks again keeps carrying its load instead of dropping
    // it on its neighbours (which then slide in turn: a rope round a post crept at mm/s).
    Vec3 anchorNew = xNew + tangential(force, sample.normal) / sample.law.stiffness;
    bool slides = false;
    if (!sample.friction.sliding) {
      // The anchor moved with the body; keep the spring within the friction cone.
      anchorNew = rod.position(s) - sample.friction.displacement + bodyMotion;
      const Vec3 stretch = tangential(xNew - anchorNew, sample.normal);
      const double limit = sample.law.friction * std::max(0.0, force.dot(sample.normal));
      const double springForce = sample.law.stiffness * stretch.norm();
      if (springForce > limit && springForce > 0.0) anchorNew = xNew - stretch * (limit / springForce);
    } else {
      const Vec3 slip = tangential(uNew - sample.bodyVelocity, sample.normal);
      slides = slip.norm() >= sample.law.frictionVelocity && slip.dot(sample.friction.direction) > 0.0;
    }
    FrictionAnchor anchor;
    anchor.body = sample.object;
    anchor.s = s;
    anchor.localPoint = toLocal(sample.object->getWorldTransform(), anchorNew - bodyMotion);
    anchor.sliding = slides;
    anchor.pressure = std::max(0.0, force.dot(sample.normal)) / sample.geometry.weight;
    anchors_.add(anchor);
  }
  anchors_.commit();
  markConcentratedLoads(rod, concentratedContactRatio);
}

void BodyContacts::limitShapeChangeWhereFrictionHolds(Rod& rod, double s, const Vec3& force, const Sample& sample) {
  // Why: a knot removal moves the curve by up to its shape error e at once, and the sample's penalty
  // spring (law.stiffness k, N/m) feels that as a force change k e that no load made. At
  // removalErrorBound (0.1 mm) that is as much as the normal force f_n = k * depth of a rope held
  // round a drum (87 um deep where it carries 10 N round 5.5 cm, 4 um where it carries 0.48 N), so
  // removals along the wrap kicked the rope loose: wrapped 2 pi at mu = 0.5 it slipped from 0.7 of
  // the capstan limit (measured, no damping; its contacts dropped from 186 to 1-4 within 0.1 s).
  // Where friction holds a load, a removal may change f_n by at most kRemovalForceShare of it
  // (docs/method.md §10). Resting samples are left free, so that a rope that has just touched a floor
  // (f_n ~ 0) still sheds the knots its first touch made.
  const double normalForce = force.dot(sample.normal);
  if (!(normalForce > 0.0 && sample.law.stiffness > 0.0)) return;
  if (tangential(force, sample.normal).norm() < kHeldFrictionShare * sample.law.friction * normalForce) return;
  rod.limitShapeChange(s, kRemovalForceShare * normalForce / sample.law.stiffness);
}

void BodyContacts::markConcentratedLoads(Rod& rod, double ratio) const {
  // A sample touches if it carries load or if its gap is zero to rounding (|distance| <=
  // kTouchingDistance). Why: a rope laid exactly on a floor has gaps of +-1e-18 m, and rounding alone
  // decides which samples the active set starts from; its first substep kept a spotty 15 of about 100
  // samples on a 1 m rope, each spot a short stretch marked as a concentrated load, and the rope
  // refined on touching the floor (9 knots inserted and 8 removed in that substep, 17 control points
  // of 16). A released sample with a real gap or depth (a rebound, a rope lifting off) is not touching.
  const auto touching = [](const Sample& sample) {
    return sample.active || std::abs(sample.geometry.contact.distance) <= kTouchingDistance;
  };
  const KnotVector& knots = rod.knots();
  std::size_t i = 0;
  while (i < samples_.size()) {
    if (!touching(samples_[i])) {
      ++i;
      continue;
    }
    // One touching stretch: touching samples on one body over consecutive capsules, at least one active.
    std::size_t j = i + 1;
    while (j < samples_.size() && touching(samples_[j]) && samples_[j].object == samples_[i].object &&
           samples_[j].geometry.capsule - samples_[j - 1].geometry.capsule <= 1)
      ++j;
    double length = 0.0, moment = 0.0;
    bool loaded = false;
    for (std::size_t k = i; k < j; ++k) {
      length += samples_[k].geometry.weight;
      moment += samples_[k].geometry.weight * samples_[k].geometry.s;
      loaded = loaded || samples_[k].active;
    }
    if (loaded && length > 0.0) {
      const double centre = moment / length;
      const int span = knots.findSpan(centre);
      const double spanLength = (knots[span + 1] - knots[span]) * rod.restMetric(centre);
      if (length < ratio * spanLength) rod.markInteraction(centre);
    }
    i = j;
  }
}

}  // namespace rope::bullet
