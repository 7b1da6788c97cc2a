// SPDX-License-Identifier: MIT
#include "bullet_bridge/rope_object.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "bullet_bridge/detail/body_state.h"
#include "bullet_bridge/detail/bullet_math.h"
#include "bullet_bridge/contact/distributed_loads.h"
#include "bullet_bridge/rope_world.h"
#include "rope/common/error.h"
#include "rope/common/prefetch.h"
#include "rope/rod/axial_force.h"
#include "rope/spline/bspline_curve.h"

namespace rope::bullet {

namespace {

void requireFinitePoint(const char* name, const btVector3& p) {
  static const char* const kAxes[3] = {".x", ".y", ".z"};
  for (int i = 0; i < 3; ++i) requireFinite(std::string(name) + kAxes[i], static_cast<double>(p[i]));
}

void requireParameter(const Rod& rod, double s) {
  requireFinite("s", s);
  if (s < rod.beginParameter() || s > rod.endParameter()) {
    throw InvalidArgument("s", formatValue(s), "must be within the rope's parameter range [" +
                                                   formatValue(rod.beginParameter()) + ", " +
                                                   formatValue(rod.endParameter()) + "]");
  }
}

}  // namespace

RopeObject::RopeObject(Rod rod, const BulletRopeSettings& settings)
    : rod_([&] {
        settings.validate();
        return std::move(rod);
      }()),
      settings_(settings),
      proxies_(std::make_unique<CapsuleProxies>(*this, settings.capsulesPerSpan, rod_.settings().radius)) {
  lastStep_.rope = this;
  proxies_->updateBoxes(rod_, settings_.initialPredictionTime, settings_.speculativeMargin);
}

RopeObject::~RopeObject() {
  if (world_ != nullptr) world_->removeRope(*this);
  for (const CutPartner& partner : cutPartners_) {
    auto& theirs = const_cast<RopeObject*>(partner.rope)->cutPartners_;
    theirs.erase(std::remove_if(theirs.begin(), theirs.end(), [this](const CutPartner& p) { return p.rope == this; }),
                 theirs.end());
  }
}

std::unique_ptr<RopeObject> RopeObject::cut(double requested) {
  requireParameter(rod_, requested);
  const double s = rod_.cutPoint(requested);  // onto a knot within minKnotSpacing (Rod::cutPoint)
  for (const Attachment& attachment : attachments_) {
    if (attachment.body != nullptr && attachment.s == s) {
      throw InvalidArgument("s", formatValue(s), "a body attachment is at the cut");
    }
  }
  std::pair<Rod, Rod> pieces = rod_.cut(s);  // throws (nothing changed) for an end or a pin at s
  auto piece = std::make_unique<RopeObject>(std::move(pieces.second), settings_);
  rod_ = std::move(pieces.first);
  for (auto it = attachments_.begin(); it != attachments_.end();) {
    if (it->s > s) {
      piece->attachments_.push_back(*it);
      it = attachments_.erase(it);
    } else {
      ++it;
    }
  }
  piece->nextAttachmentId_ = nextAttachmentId_;
  piece->winches_[1] = winches_[1];  // the winch at the end goes with the end
  winches_[1] = Winch();
  // A winchTo target is the whole rope's rest length: each piece's winch aims at its own share.
  if (piece->winches_[1].targetLength >= 0.0) {
    piece->winches_[1].targetLength = std::max(0.0, piece->winches_[1].targetLength - rod_.restLength());
  }
  if (winches_[0].targetLength >= 0.0) {
    winches_[0].targetLength = std::max(0.0, winches_[0].targetLength - piece->rod_.restLength());
  }
  // Its parameter range changed: the stick state of its distributed rope-rope contacts is let go.
  if (world_ != nullptr) world_->ropeRopeContacts_.forget(*this);
  cutPartners_.push_back({piece.get(), s, s});
  piece->cutPartners_.push_back({this, s, s});
  contacts_.clear();
  lastStep_ = RopeStepRecord();
  lastStep_.rope = this;
  proxies_->updateBoxes(rod_, settings_.initialPredictionTime, settings_.speculativeMargin);
  if (world_ != nullptr) world_->addRope(*piece);
  return piece;
}

void RopeObject::applyForce(double s, const btVector3& force) { rod_.addForce(s, toVec(force)); }

void RopeObject::applyImpulse(double s, const btVector3& impulse) { rod_.addImpulse(s, toVec(impulse)); }

void RopeObject::applyDistributedForce(double s0, double s1, const btVector3& forcePerLength) {
  requireFinite("s0", s0);
  requireFinite("s1", s1);
  if (s0 < rod_.beginParameter()) {
    throw InvalidArgument("s0", formatValue(s0), "must be >= the rope's beginParameter " + formatValue(rod_.beginParameter()));
  }
  if (s1 > rod_.endParameter()) {
    throw InvalidArgument("s1", formatValue(s1), "must be <= the rope's endParameter " + formatValue(rod_.endParameter()));
  }
  if (!(s1 > s0)) throw InvalidArgument("s1", formatValue(s1), "must be > s0 = " + formatValue(s0));
  static const char* const kNames[3] = {"forcePerLength[0]", "forcePerLength[1]", "forcePerLength[2]"};
  for (int i = 0; i < 3; ++i) requireFinite(kNames[i], static_cast<double>(forcePerLength[i]));
  queueDistributedForce(rod_, s0, s1, toVec(forcePerLength));
}

double RopeObject::tension(double s) const { return axialForce(rod_, s); }  // validates s

double RopeObject::attachmentTension(int id) const {
  return tension(attachments_[static_cast<std::size_t>(findAttachment(id))].s);
}

void RopeObject::enterWorld(RopeWorld& world, btCollisionWorld& collisionWorld) {
  proxies_->addToWorld(collisionWorld, settings_.collisionGroup, settings_.collisionMask);
  world_ = &world;
  proxies_->updateBoxes(rod_, settings_.initialPredictionTime, settings_.speculativeMargin);
}

void RopeObject::setCollisionFilter(int group, int mask) {
  if (group == 0) throw InvalidArgument("group", "0", "must have at least one bit set");
  if (world_ != nullptr && world_->stepping()) {
    throw InvalidArgument("rope", "its world is stepping", "change the collision filter between steps");
  }
  settings_.collisionGroup = group;
  settings_.collisionMask = mask;
  proxies_->setFilter(group, mask);
}

void RopeObject::leaveWorld() {
  proxies_->removeFromWorld();
  bodyContacts_.reset();
  world_ = nullptr;
  bodyAttachmentCounts_ = nullptr;  // the RopeWorld owns the counts
  contacts_.clear();
}

int RopeObject::findAttachment(int id) const {
  for (std::size_t i = 0; i < attachments_.size(); ++i) {
    if (attachments_[i].id == id) return static_cast<int>(i);
  }
  throw InvalidArgument("id", std::to_string(id), "is not an attachment of this rope");
}

int RopeObject::attachToBody(double s, btRigidBody& body, const btVector3& localPoint,
                             const AttachmentSettings& settings) {
  requireParameter(rod_, s);
  requireFinitePoint("localPoint", localPoint);
  settings.validate();
  if (world_ == nullptr) throw InvalidArgument("rope", "not in a world", "must be added to a RopeWorld first");
  if (!world_->containsBody(body)) {
    throw InvalidArgument("body", "not in the rope's world", "must be added to the Bullet world first");
  }
  requireNewBodyPoint(s, body);
  Attachment attachment;
  attachment.id = nextAttachmentId_++;
  attachment.s = s;
  attachment.body = &body;
  attachment.bodyIndexHint = body.getWorldArrayIndex();
  attachment.localPoint = localPoint;
  attachment.settings = settings;
  attachments_.push_back(attachment);
  return attachment.id;
}

int RopeObject::clampToBody(double s, btRigidBody& body, const btVector3& localPoint,
                            const btVector3& localDirection, const AttachmentSettings& settings) {
  requireFinitePoint("localDirection", localDirection);
  if (!(localDirection.length2() > btScalar(0))) {
    throw InvalidArgument("localDirection", "(0, 0, 0)", "must have a length > 0");
  }
  const int id = attachToBody(s, body, localPoint, settings);  // every other check; nothing added if it throws
  Attachment& attachment = attachments_.back();
  attachment.clamp = true;
  attachment.localDirection = localDirection.normalized();
  return id;
}

int RopeObject::attachToPoint(double s, const btVector3& point) {
  requireParameter(rod_, s);
  requireFinitePoint("point", point);
  Attachment attachment;
  attachment.pinId = rod_.pin(s, toVec(point));  // throws (rod unchanged) for a pin already at s
  attachment.id = nextAttachmentId_++;
  attachment.s = s;
  attachments_.push_back(attachment);
  return attachment.id;
}

void RopeObject::setAttachmentTarget(int id, const btVector3& point) {
  const int index = findAttachment(id);
  const Attachment& attachment = attachments_[static_cast<std::size_t>(index)];
  if (attachment.body != nullptr) {
    throw InvalidArgument("id", std::to_string(id), "is a body attachment (its target is the body)");
  }
  requireFinitePoint("point", point);
  rod_.setPinTarget(attachment.pinId, toVec(point));
}

void RopeObject::removeAttachment(int id) {
  const int index = findAttachment(id);
  const Attachment& attachment = attachments_[static_cast<std::size_t>(index)];
  if (attachment.body == nullptr) rod_.releasePin(attachment.pinId);
  attachments_.erase(attachments_.begin() + index);
}

double RopeObject::bodyFriction(const btCollisionObject& body) const {
  if (world_ != nullptr && world_->bodyFrictionCombiner_) return world_->bodyFrictionCombiner_(*this, body);
  return combinedFriction(settings_.friction, static_cast<double>(body.getFriction()));
}

bool RopeObject::attachedNear(const btCollisionObject& object, double s0, double s1) const {
  const double reach = 4.0 * rod_.settings().radius;
  for (const Attachment& attachment : attachments_) {
    if (attachment.body == &object && attachment.s >= s0 - reach && attachment.s <= s1 + reach) return true;
  }
  return false;
}

void RopeObject::substep(const std::vector<const btCollisionObject*>& candidates, double h) {
  beginSubstep(candidates, h);
  endSubstep(h);
}

int RopeObject::attachmentsOn(const btRigidBody* body) const {
  if (bodyAttachmentCounts_ != nullptr && !bodyAttachmentCounts_->empty()) {
    const auto found = std::lower_bound(bodyAttachmentCounts_->begin(), bodyAttachmentCounts_->end(),
                                        std::pair<const btRigidBody*, int>(body, 0));
    if (found != bodyAttachmentCounts_->end() && found->first == body) return std::max(1, found->second);
  }
  int count = 0;
  for (const Attachment& attachment : attachments_) count += attachment.body == body ? 1 : 0;
  return std::max(1, count);
}

void RopeObject::queueAttachments(double h) {
  for (std::size_t i = 0; i < attachments_.size(); ++i) {
    Attachment& attachment = attachments_[i];
    attachment.lastForce.setZero();
    attachment.lastMoment.setZero();
    btRigidBody* body = attachment.body;
    if (body == nullptr || body->getBroadphaseHandle() == nullptr) continue;  // pins act in the rod
    if (!bodyStateFinite(*body)) {  // a NaN transform, velocity or mass must not poison the rope
      ++lastStep_.skippedBodies;
      continue;
    }
    const btVector3 point = body->getCenterOfMassTransform() * attachment.localPoint;
    const btVector3 arm = point - body->getCenterOfMassPosition();
    Vec3 bodyVelocity = toVec(body->getVelocityInLocalPoint(arm));
    // A dynamic body moves on under its own forces (gravity included) during the step as well as
    // under the rope's impulse; without them a 10 kg ball at 1/60 s hung 3.7 mm off the rope's end
    // instead of its weight / stiffness, 1.0 mm.
    if (dynamicBody(*body) != nullptr) bodyVelocity += h * pointAccelerationFromForces(*body, arm);
    PendingSpring pending;
    pending.s = attachment.s;
    pending.velocity = rod_.velocity(attachment.s);
    pending.spring = attachmentSpring(attachment.settings.stiffness, attachment.settings.damping,
                                      rod_.position(attachment.s), toVec(point), pending.velocity, bodyVelocity, h);
    if (dynamicBody(*body) != nullptr) {
      // The spring acts in series with the body point's inertia, shared among the body's attachments.
      const double sharing = static_cast<double>(attachmentsOn(body));
      seriesWithBody(pending.spring, sharing * pointInverseMass(*body, arm), h);
    }
    pending.body = dynamicBody(*body);
    pending.point = point;
    pending.attachment = static_cast<int>(i);
    pending.tangent = false;
    pending_.push_back(pending);
    if (attachment.clamp) queueClampTangent(attachment, *body, static_cast<int>(i), h);
  }
}

void RopeObject::queueClampTangent(const Attachment& attachment, btRigidBody& body, int index, double h) {
  double stiffness = attachment.settings.angularStiffness;
  double damping = attachment.settings.angularDamping;
  if (dynamicBody(body) != nullptr) {
    // Smallest principal moment of inertia: the explicit angular impulse's stability bound.
    const btVector3 inertia = body.getInvInertiaDiagLocal();
    capForBody(static_cast<double>(std::max({inertia.x(), inertia.y(), inertia.z()})), h,
               settings_.bodyStabilityFactor, stiffness, damping);
  }
  const Vec3 direction = toVec(body.getCenterOfMassTransform().getBasis() * attachment.localDirection).normalized();
  const CurvePoint rate = evaluateCurve(rod_.knots(), rod_.velocities(), attachment.s);
  PendingSpring pending;
  pending.s = attachment.s;
  pending.derivative = evaluateCurve(rod_.knots(), rod_.controlPoints(), attachment.s).firstDerivative;
  pending.velocity = rate.firstDerivative;
  pending.tangent = true;
  pending.spring = clampTangentSpring(stiffness, damping, rod_.restMetric(attachment.s), pending.derivative,
                                      pending.velocity, direction, toVec(body.getAngularVelocity()), h);
  pending.body = dynamicBody(body);
  pending.point = body.getCenterOfMassPosition();
  pending.attachment = index;
  pending_.push_back(pending);
}

StepReport RopeObject::solveTrialWithContacts(double h) {
  // Unilateral contact and Coulomb friction by a small active set (contact/body_contacts.h: update): samples
  // that come out pulling are released, sticking samples that need more than mu f_n slide, and the
  // trial step is solved again, at most kMaxContactSolvePasses times. The rod itself does not change
  // until endSubstep commits the last trial.
  StepReport report;
  for (int pass = 1;; ++pass) {
    lastStep_.solvePasses = pass;
    queueTrialLoads();
    report = rod_.solveTrial(h);
    if (!report.ok || lastStep_.contacts == 0) break;
    if (pass >= kMaxContactSolvePasses) {
      lastStep_.contactsUnsettled = !bodyContacts_.settled(rod_, h);
      break;
    }
    if (!bodyContacts_.update(rod_, h, contacts_, lastStep_)) break;
  }
  // The passes are steps linearised once about the start (the rod does not relinearise them while
  // line-contact samples are queued), and a trial in which a body drags the rope sideways, or a coiled
  // rope springs off a drum, can hold far more stretching than the step's quadratic model: 1,652 J
  // where a 50 m/s box hits a pinned rope (energy +61 % in one substep), 1,928 J from 35 J on a rope
  // round a frictional drum (reliability_extremes_test). Such a trial is solved once more, with the
  // same loads and the stretching relinearised about it (Rod::solveTrial; docs/method.md §8), after
  // the last pass, not in the passes: relinearised passes feed the friction updates between them, and
  // on the drum ran away (6.3 MJ within five substeps), while one solve after them takes the box's
  // growth away and lowers the drum's energy peak from 2,011 J to 594 J (measured 2026-12-02).
  if (report.ok && lastStep_.contacts > 0 && rod_.trialNeedsRelinearisation()) {
    lastStep_.contactRelinearised = true;
    queueTrialLoads();
    report = rod_.solveTrial(h, /*relineariseInContact=*/true);
  }
  return report;
}

void RopeObject::queueTrialLoads() {
  rod_.clearLoads();
  rod_.addLoads(userLoads_);
  for (const PendingSpring& pending : pending_) {
    if (pending.tangent) {
      rod_.addTangentSpring(pending.s, pending.spring.force, pending.spring.stiffness, pending.spring.damping);
    } else {
      rod_.addSpring(pending.s, pending.spring.force, pending.spring.stiffness, pending.spring.damping);
    }
  }
  bodyContacts_.queue(rod_);
}

void RopeObject::beginSubstep(const std::vector<const btCollisionObject*>& candidates, double h) {
  prepareSubstep(h);
  solveSubstepTrial(candidates, h);
}

void RopeObject::prepareSubstep(double h) {
  requirePositive("h", h);
  runWinches(h);  // winch.h: the ends move before anything reads the rope
  if (settings_.fluidDensity > 0.0) {
    // Drag at the state the substep starts from (contact/distributed_loads.h), queued with the user's loads.
    const double diameter = 2.0 * rod_.settings().radius;
    DragLaw drag;
    drag.normal = 0.5 * settings_.fluidDensity * diameter * settings_.normalDragCoefficient;
    drag.tangential = 0.5 * settings_.fluidDensity * 3.14159265358979323846 * diameter * settings_.tangentialDragCoefficient;
    drag.wind = toVec(settings_.windVelocity);
    queueDrag(rod_, drag);
  }
  rod_.takeLoads(userLoads_);  // queued on rod() or by applyForce since the last substep
  // Rope-rope contact corrects the trial after the body contacts' passes, which would spoil friction
  // bounds made exact before it: a rope that touched ropes last substep keeps the pass-by-pass ones.
  bodyContacts_.setExactBounds(lastStep_.ropeContacts == 0);
  nearRopesBefore_ = nearRopes_;
  nearRopes_ = false;
  contacts_.clear();
  pending_.clear();
  lastStep_ = RopeStepRecord();
  lastStep_.rope = this;
  substepStart_ = std::chrono::steady_clock::now();
  proxies_->rebuild(rod_);
}

void RopeObject::solveSubstepTrial(const std::vector<const btCollisionObject*>& candidates, double h) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = substepStart_;
  bodyContacts_.gather(
      rod_, *proxies_, candidates, settings_,
      [this](const btCollisionObject& object, double s0, double s1) { return attachedNear(object, s0, s1); },
      [this](const btCollisionObject& object) { return bodyFriction(object); }, h, contacts_, lastStep_);
  for (RopeContactRecord& record : contacts_) record.rope = this;
  // Contact forces are not smooth in time: a substep with body contact candidates, or after one with
  // rope-rope candidates, is a backward-Euler step (Rod::restartTimeIntegration); free and attached
  // stretches of motion keep the rod's second-order BDF2. Knot removal there is judged by the shape
  // (RemovalCriterion::kMechanicalOutOfContact): contact jitter is far above the mechanical floors.
  if (!contacts_.empty() || nearRopesBefore_) {
    rod_.restartTimeIntegration();
    rod_.markContact();
  }

  queueAttachments(h);

  const Clock::time_point solveStart = Clock::now();
  const StepReport report = solveTrialWithContacts(h);
  lastStep_.ok = report.ok;
  lastStep_.failure = report.failure;
  if (!report.ok) rod_.clearLoads();  // the rod keeps its state; no trial for rope-rope contact
  lastStep_.contactSeconds = std::chrono::duration<double>(solveStart - start).count();
  lastStep_.solveSeconds = std::chrono::duration<double>(Clock::now() - solveStart).count();
}

void RopeObject::endSubstep(double h) {
  finishSubstep(h);
  announceBox();
}

void RopeObject::announceBox() {
  // The broadphase update is the last part of the refit (RopeStepRecord::proxySeconds).
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  proxies_->announceObjectBox();
  lastStep_.proxySeconds += std::chrono::duration<double>(Clock::now() - start).count();
}

bool RopeObject::finishesAlone() const {
  for (const PendingSpring& pending : pending_) {
    if (pending.body != nullptr) return false;
  }
  return !bodyContacts_.pushesBodies();
}

void RopeObject::prefetchObject() const { prefetchBytes(this, sizeof(*this)); }

void RopeObject::prefetchParts() const { prefetchBytes(proxies_.get(), sizeof(CapsuleProxies)); }

void RopeObject::prefetchState() const {
  rod_.prefetchState();
  prefetchContactState();
}

void RopeObject::prefetchTrial() const {
  rod_.prefetch();  // the rod's state and the step storage it holds now
  prefetchContactState();
}

void RopeObject::prefetchContactState() const {
  proxies_->prefetch();
  bodyContacts_.prefetch();
  prefetchVector(contacts_);
  prefetchVector(attachments_);
  prefetchVector(attachmentLoads_);
}

void RopeObject::prefetchRecords() const {
  prefetchVector(contacts_);
  prefetchVector(attachmentLoads_);
  prefetchBytes(&proxies_->object(), sizeof(btCollisionObject));
}

void RopeObject::finishSubstep(double h) {
  requirePositive("h", h);
  using Clock = std::chrono::steady_clock;
  const Clock::time_point commitStart = Clock::now();
  if (lastStep_.ok && rod_.hasTrial()) {
    // Forces from the final trial (rope-rope contact may have corrected it): exactly what the rope's
    // implicit system integrated for each spring.
    for (const PendingSpring& pending : pending_) {
      if (pending.tangent) {
        // The generalised force on C'(s) is a pure moment C' x f on the rope; the body gets its opposite.
        const Vec3 rateNew = evaluateCurve(rod_.knots(), rod_.trialVelocities(), pending.s).firstDerivative;
        const Vec3 moment = pending.derivative.cross(endOfStepForce(pending.spring, pending.velocity, rateNew, h));
        attachments_[static_cast<std::size_t>(pending.attachment)].lastMoment += toBullet(moment);
        if (pending.body != nullptr) {
          pending.body->applyTorqueImpulse(toBullet(-moment * h));
          pending.body->activate();
        }
        continue;
      }
      const Vec3 force = endOfStepForce(pending.spring, pending.velocity, rod_.trialVelocity(pending.s), h);
      attachments_[static_cast<std::size_t>(pending.attachment)].lastForce += toBullet(force);
      if (pending.body != nullptr) {
        // Newton's third law: the body gets exactly the opposite of what the rope felt over the step.
        pending.body->applyImpulse(toBullet(-force * h), pending.point - pending.body->getCenterOfMassPosition());
        pending.body->activate();
      }
    }
    bodyContacts_.finish(rod_, h, settings_.concentratedContactRatio, contacts_);
    const StepReport report = rod_.commitTrial();
    lastStep_.ok = report.ok;
    lastStep_.failure = report.failure;
    lastStep_.insertions = report.insertions;
    lastStep_.removals = report.removals;
    lastStep_.maxInsertionRelaxation = report.maxInsertionRelaxation;
    lastStep_.unrelaxedInsertionEnergy = report.unrelaxedInsertionEnergy;
  } else {
    lastStep_.ok = false;
    if (*lastStep_.failure == '\0') lastStep_.failure = "the rope's trial step was discarded";
    rod_.clearLoads();
  }
  if (!lastStep_.ok) {
    for (RopeContactRecord& record : contacts_) {
      record.active = false;
      record.force.setZero();
    }
    lastStep_.contacts = 0;
  }
  lastStep_.controlPoints = rod_.controlPointCount();
  pending_.clear();
  attachmentLoads_.clear();
  for (const Attachment& attachment : attachments_) {
    RopeAttachmentRecord record;
    record.rope = this;
    record.id = attachment.id;
    record.s = attachment.s;
    record.body = attachment.body;
    record.force = attachment.lastForce;
    record.tension = tension(attachment.s);
    attachmentLoads_.push_back(record);
  }
  const Clock::time_point proxyStart = Clock::now();
  lastStep_.proxyOverflows = proxies_->updateBoxesDeferred(rod_, h, settings_.speculativeMargin);
  const Clock::time_point end = Clock::now();
  lastStep_.solveSeconds += std::chrono::duration<double>(proxyStart - commitStart).count();
  lastStep_.proxySeconds = std::chrono::duration<double>(end - proxyStart).count();
}

}  // namespace rope::bullet
