#include "bullet_bridge/rope_object.h"

#include <BulletCollision/BroadphaseCollision/btBroadphaseProxy.h>
#include <LinearMath/btAabbUtil2.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "bullet_bridge/body_state.h"
#include "bullet_bridge/find_contacts.h"
#include "bullet_bridge/rope_world.h"
#include "rope/common/error.h"

namespace rope::bullet {

namespace {

Vec3 toVec(const btVector3& v) {
  return Vec3(static_cast<double>(v.x()), static_cast<double>(v.y()), static_cast<double>(v.z()));
}

btVector3 toBullet(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()), static_cast<btScalar>(v.z()));
}

bool isFinite(const btVector3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

bool isFinite(const btTransform& t) {
  return isFinite(t.getOrigin()) && isFinite(t.getBasis()[0]) && isFinite(t.getBasis()[1]) &&
         isFinite(t.getBasis()[2]);
}

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

// A dynamic body that takes impulses, or nullptr for static and kinematic objects.
btRigidBody* dynamicBody(const btCollisionObject& object) {
  btRigidBody* body = btRigidBody::upcast(const_cast<btCollisionObject*>(&object));
  if (body == nullptr || body->isStaticOrKinematicObject() || !(body->getInvMass() > 0)) return nullptr;
  return body;
}

Vec3 pointVelocity(const btCollisionObject& object, const btVector3& point) {
  const btRigidBody* body = btRigidBody::upcast(&object);
  if (body == nullptr) return Vec3::Zero();
  return toVec(body->getVelocityInLocalPoint(point - body->getCenterOfMassPosition()));
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
  cutPartners_.push_back({piece.get(), s, s});
  piece->cutPartners_.push_back({this, s, s});
  contacts_.clear();
  lastStep_ = RopeStepRecord();
  lastStep_.rope = this;
  proxies_->updateBoxes(rod_, settings_.initialPredictionTime, settings_.speculativeMargin);
  if (world_ != nullptr) world_->addRope(*piece);
  return piece;
}

void RopeObject::enterWorld(RopeWorld& world, btCollisionWorld& collisionWorld) {
  proxies_->addToWorld(collisionWorld, settings_.collisionGroup, settings_.collisionMask);
  world_ = &world;
  proxies_->updateBoxes(rod_, settings_.initialPredictionTime, settings_.speculativeMargin);
}

void RopeObject::leaveWorld() {
  proxies_->removeFromWorld();
  world_ = nullptr;
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

bool RopeObject::attachedNear(const btCollisionObject& object, double s0, double s1) const {
  const double reach = 4.0 * rod_.settings().radius;
  for (const Attachment& attachment : attachments_) {
    if (attachment.body == &object && attachment.s >= s0 - reach && attachment.s <= s1 + reach) return true;
  }
  return false;
}

void RopeObject::queueSpring(double s, double weight, const ContactSpring& spring, btRigidBody* body,
                             const btVector3& point, int record, int attachment) {
  PendingSpring pending;
  pending.s = s;
  pending.velocity = rod_.velocity(s);
  pending.weight = weight;
  pending.spring.force = weight * spring.force;
  pending.spring.stiffness = weight * spring.stiffness;
  pending.spring.damping = weight * spring.damping;
  pending.body = body;
  pending.point = point;
  pending.record = record;
  pending.attachment = attachment;
  pending_.push_back(pending);
}

void RopeObject::gatherContacts(const std::vector<const btCollisionObject*>& candidates, double h) {
  const double margin = settings_.speculativeMargin;
  const btScalar pad = static_cast<btScalar>(rod_.settings().radius + margin);
  for (const btCollisionObject* object : candidates) {
    if (!isFinite(object->getWorldTransform())) {
      ++lastStep_.skippedBodies;  // a NaN body must not poison the rope
      continue;
    }
    const btBroadphaseProxy* handle = object->getBroadphaseHandle();
    if (handle == nullptr) continue;
    btRigidBody* body = dynamicBody(*object);
    // How far the body's surface can move in the step: linear speed plus spin times its box's reach.
    double bodyReach = 0.0;
    if (const btRigidBody* rigid = btRigidBody::upcast(object)) {
      const double spin = static_cast<double>(rigid->getAngularVelocity().length());
      const double extent = 0.5 * static_cast<double>((handle->m_aabbMax - handle->m_aabbMin).length());
      bodyReach = h * (static_cast<double>(rigid->getLinearVelocity().length()) + spin * extent);
      if (!std::isfinite(bodyReach)) {
        ++lastStep_.skippedBodies;
        continue;
      }
    }
    int previousEndContact = -2;  // capsule whose last contact with this body was at its end (t = 1)
    for (int i = 0; i < proxies_->size(); ++i) {
      const Capsule capsule = proxies_->capsule(i);
      const CapsuleProxy& capsuleProxy = proxies_->proxy(i);
      // Speculative distance: the configured margin plus what rope and body can close in this step,
      // so a fast rope meets a thin plate before it has passed it.
      const double ropeReach =
          h * std::max(rod_.velocity(capsuleProxy.s0).norm(), rod_.velocity(capsuleProxy.s1).norm());
      const double reach = margin + ropeReach + bodyReach;
      const btScalar grow = pad + static_cast<btScalar>(ropeReach + bodyReach);
      btVector3 lo = capsule.a, hi = capsule.a;
      lo.setMin(capsule.b);
      hi.setMax(capsule.b);
      lo -= btVector3(grow, grow, grow);
      hi += btVector3(grow, grow, grow);
      if (!TestAabbAgainstAabb2(lo, hi, handle->m_aabbMin, handle->m_aabbMax)) continue;
      scratch_.clear();
      try {
        findContacts(capsule, *object, reach, scratch_);
      } catch (const InvalidArgument&) {
        ++lastStep_.skippedBodies;  // a shape the narrowphase does not support
        break;
      }
      const CapsuleProxy& proxy = proxies_->proxy(i);
      if (attachedNear(*object, proxy.s0, proxy.s1)) continue;
      bool endContact = false;
      for (const Contact& contact : scratch_) {
        const double t = std::clamp(static_cast<double>(contact.t), 0.0, 1.0);
        // Neighbouring capsules share their end point: a contact there counts once (a rope lying
        // along a face touches it at the capsules' ends, where GJK puts a parallel segment's contact).
        if (t <= 0.0 && previousEndContact == i - 1) continue;
        endContact = endContact || t >= 1.0;
        const double s = std::clamp(proxy.s0 + t * (proxy.s1 - proxy.s0), proxy.s0, proxy.s1);
        const Vec3 normal = toVec(contact.normal);
        const double distance = static_cast<double>(contact.distance);
        const Vec3 u = rod_.velocity(s);
        const Vec3 bodyVelocity = pointVelocity(*object, contact.pointOnBody);

        RopeContactRecord record;
        record.rope = this;
        record.body = object;
        record.s = s;
        record.point = contact.pointOnBody;
        record.normal = contact.normal;
        record.depth = -distance;
        lastStep_.maxPenetration = std::max(lastStep_.maxPenetration, -distance);
        if (contactActive(distance, normal, u, bodyVelocity, h)) {
          ContactLaw law;
          law.stiffness = settings_.contactStiffness;
          law.damping = settings_.contactDamping;
          law.speculativeDamping = settings_.speculativeDamping;
          law.friction = settings_.friction;
          law.frictionVelocity = settings_.frictionVelocity;
          if (body != nullptr) {
            const double inverseMass =
                static_cast<double>(body->computeImpulseDenominator(contact.pointOnBody, contact.normal));
            capForBody(inverseMass, h, settings_.bodyStabilityFactor, law.stiffness, law.damping);
            double unusedStiffness = law.stiffness;
            capForBody(inverseMass, h, settings_.bodyStabilityFactor, unusedStiffness, law.speculativeDamping);
            law.frictionDampingLimit = std::numeric_limits<double>::max();
            capForBody(inverseMass, h, settings_.bodyStabilityFactor, unusedStiffness, law.frictionDampingLimit);
          }
          const ContactSpring spring = contactSpring(law, distance, normal, u, bodyVelocity, h);
          const int recordIndex = static_cast<int>(contacts_.size());
          inputs_.resize(contacts_.size() + 1);
          inputs_.back() = ContactInput{law, distance, normal, u, bodyVelocity, -1.0};
          // Lever rule onto the knots around s unless s is far from every knot (contactKnotSpacing).
          const KnotVector& knots = rod_.knots();
          const int span = knots.findSpan(s);
          const double left = knots[span], right = knots[span + 1];
          const double nearest = std::min(s - left, right - s);
          if (nearest <= 0.0 || nearest > settings_.contactKnotSpacing) {
            queueSpring(s, 1.0, spring, body, contact.pointOnBody, recordIndex, -1);
          } else {
            const double leftWeight = (right - s) / (right - left);
            queueSpring(left, leftWeight, spring, body, contact.pointOnBody, recordIndex, -1);
            queueSpring(right, 1.0 - leftWeight, spring, body, contact.pointOnBody, recordIndex, -1);
          }
          record.active = true;
          ++lastStep_.contacts;
        }
        contacts_.push_back(record);
      }
      if (endContact) previousEndContact = i;
    }
  }
}

void RopeObject::substep(const std::vector<const btCollisionObject*>& candidates, double h) {
  beginSubstep(candidates, h);
  endSubstep(h);
}

void RopeObject::beginSubstep(const std::vector<const btCollisionObject*>& candidates, double h) {
  requirePositive("h", h);
  contacts_.clear();
  inputs_.clear();
  pending_.clear();
  lastStep_ = RopeStepRecord();
  lastStep_.rope = this;
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  proxies_->rebuild(rod_);
  gatherContacts(candidates, h);

  for (std::size_t i = 0; i < attachments_.size(); ++i) {
    Attachment& attachment = attachments_[i];
    attachment.lastForce.setZero();
    btRigidBody* body = attachment.body;
    if (body == nullptr || body->getBroadphaseHandle() == nullptr) continue;  // pins act in the rod
    if (!bodyStateFinite(*body)) {  // a NaN transform, velocity or mass must not poison the rope
      ++lastStep_.skippedBodies;
      continue;
    }
    const btVector3 point = body->getCenterOfMassTransform() * attachment.localPoint;
    const btVector3 arm = point - body->getCenterOfMassPosition();
    const Vec3 bodyVelocity = toVec(body->getVelocityInLocalPoint(arm));
    double stiffness = attachment.settings.stiffness;
    double damping = attachment.settings.damping;
    if (dynamicBody(*body) != nullptr) {
      // Smallest effective mass of the point over all directions (conservative bound).
      const btVector3 inertia = body->getInvInertiaDiagLocal();
      const double maxInverseInertia = static_cast<double>(std::max({inertia.x(), inertia.y(), inertia.z()}));
      const double inverseMass =
          static_cast<double>(body->getInvMass()) + static_cast<double>(arm.length2()) * maxInverseInertia;
      capForBody(inverseMass, h, settings_.bodyStabilityFactor, stiffness, damping);
    }
    const ContactSpring spring = attachmentSpring(stiffness, damping, rod_.position(attachment.s), toVec(point),
                                                  rod_.velocity(attachment.s), bodyVelocity, h);
    queueSpring(attachment.s, 1.0, spring, dynamicBody(*body), point, -1, static_cast<int>(i));
  }

  const Clock::time_point solveStart = Clock::now();
  // Unilateral contact by a small active set: a contact whose force at the end of the step pulls the
  // rope onto the body (the rope left the surface during the step, or a speculative contact did not
  // close) is dropped and the trial step solved again, at most kMaxSolvePasses times. The rod itself
  // does not change until endSubstep commits the last trial.
  constexpr int kMaxSolvePasses = 4;
  const bool mayRetry = lastStep_.contacts > 0;
  StepReport report;
  for (int pass = 1;; ++pass) {
    lastStep_.solvePasses = pass;
    rod_.clearLoads();
    for (const PendingSpring& pending : pending_) {
      if (pending.record >= 0 && !contacts_[static_cast<std::size_t>(pending.record)].active) continue;
      rod_.addSpring(pending.s, pending.spring.force, pending.spring.stiffness, pending.spring.damping);
    }
    report = rod_.solveTrial(h);
    if (!report.ok || !mayRetry || pass >= kMaxSolvePasses) break;
    std::vector<Vec3>& totals = forceTotals_;
    totals.assign(contacts_.size(), Vec3::Zero());
    for (const PendingSpring& pending : pending_) {
      if (pending.record < 0) continue;
      if (!contacts_[static_cast<std::size_t>(pending.record)].active) continue;
      totals[static_cast<std::size_t>(pending.record)] +=
          endOfStepForce(pending.spring, pending.velocity, rod_.trialVelocity(pending.s), h);
    }
    bool changed = false;
    for (std::size_t i = 0; i < contacts_.size(); ++i) {
      RopeContactRecord& record = contacts_[i];
      if (!record.active) continue;
      ContactInput& input = inputs_[i];
      const double normalForce = totals[i].dot(input.normal);
      if (normalForce < 0.0) {
        record.active = false;
        --lastStep_.contacts;
        changed = true;
        continue;
      }
      if (!(input.law.friction > 0.0)) continue;
      const double estimate =
          input.frictionNormalForce >= 0.0 ? input.frictionNormalForce : std::max(0.0, -input.law.stiffness * input.distance);
      if (std::abs(normalForce - estimate) <= 0.05 * std::max(normalForce, estimate)) continue;
      input.frictionNormalForce = normalForce;
      changed = true;
    }
    if (!changed) break;
    // Re-evaluate the springs of the contacts whose friction bound changed.
    for (PendingSpring& pending : pending_) {
      if (pending.record < 0) continue;
      const ContactInput& input = inputs_[static_cast<std::size_t>(pending.record)];
      if (!(input.frictionNormalForce >= 0.0)) continue;
      const ContactSpring spring = contactSpring(input.law, input.distance, input.normal, input.velocity,
                                                 input.bodyVelocity, h, input.frictionNormalForce);
      pending.spring.force = pending.weight * spring.force;
      pending.spring.stiffness = pending.weight * spring.stiffness;
      pending.spring.damping = pending.weight * spring.damping;
    }
  }
  lastStep_.ok = report.ok;
  lastStep_.failure = report.failure;
  if (!report.ok) rod_.clearLoads();  // the rod keeps its state; no trial for rope-rope contact
  lastStep_.contactSeconds = std::chrono::duration<double>(solveStart - start).count();
  lastStep_.solveSeconds = std::chrono::duration<double>(Clock::now() - solveStart).count();
}

void RopeObject::endSubstep(double h) {
  requirePositive("h", h);
  using Clock = std::chrono::steady_clock;
  const Clock::time_point commitStart = Clock::now();
  if (lastStep_.ok && rod_.hasTrial()) {
    // Forces from the final trial (rope-rope contact may have corrected it): exactly what the rope's
    // implicit system integrated for each spring.
    for (const PendingSpring& pending : pending_) {
      if (pending.record >= 0 && !contacts_[static_cast<std::size_t>(pending.record)].active) continue;
      const Vec3 force = endOfStepForce(pending.spring, pending.velocity, rod_.trialVelocity(pending.s), h);
      if (pending.record >= 0) {
        contacts_[static_cast<std::size_t>(pending.record)].force += toBullet(force);
      } else {
        attachments_[static_cast<std::size_t>(pending.attachment)].lastForce += toBullet(force);
      }
      if (pending.body != nullptr) {
        // Newton's third law: the body gets exactly the opposite of what the rope felt over the step.
        pending.body->applyImpulse(toBullet(-force * h), pending.point - pending.body->getCenterOfMassPosition());
        pending.body->activate();
      }
    }
    for (RopeContactRecord& record : contacts_) {
      if (!record.active) continue;
      const Vec3 normal = toVec(record.normal);
      const Vec3 slip = rod_.trialVelocity(record.s) - pointVelocity(*record.body, record.point);
      record.sticking = (slip - normal * normal.dot(slip)).norm() < settings_.frictionVelocity;
    }
    const StepReport report = rod_.commitTrial();
    lastStep_.ok = report.ok;
    lastStep_.failure = report.failure;
    lastStep_.insertions = report.insertions;
    lastStep_.removals = report.removals;
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
  const Clock::time_point proxyStart = Clock::now();
  lastStep_.proxyOverflows = proxies_->updateBoxes(rod_, h, settings_.speculativeMargin);
  const Clock::time_point end = Clock::now();
  lastStep_.solveSeconds += std::chrono::duration<double>(proxyStart - commitStart).count();
  lastStep_.proxySeconds = std::chrono::duration<double>(end - proxyStart).count();
}

}  // namespace rope::bullet
