// SPDX-License-Identifier: MIT
// RopeObject: attachments that would break the rope are refused; what a RopeWorld does when a rope's
// substep cannot run or goes wrong (rope_warnings.h; nothing there throws, it runs inside Bullet's
// stepSimulation).
#include <LinearMath/btAabbUtil2.h>

#include <algorithm>

#include "bullet_bridge/detail/body_state.h"
#include "bullet_bridge/find_contacts.h"
#include "bullet_bridge/contact/kinematic_push.h"
#include "bullet_bridge/rope_object.h"
#include "bullet_bridge/detail/world_membership.h"
#include "rope/common/error.h"
#include "rope/spline/arc_length.h"

namespace rope::bullet {

void RopeObject::requireNewBodyPoint(double s, const btRigidBody& body) const {
  for (const Attachment& other : attachments_) {
    if (other.body != &body) continue;
    const double gap = arcLength(rod_.knots(), rod_.restControlPoints(), std::min(s, other.s), std::max(s, other.s));
    if (!(gap >= rod_.settings().minKnotSpacing)) {
      throw InvalidArgument("s", formatValue(s),
                            "the body is already attached at s = " + formatValue(other.s) + " (attachment " +
                                std::to_string(other.id) + "), closer than settings.minKnotSpacing");
    }
  }
}

void RopeObject::dropDepartedAttachments(const btCollisionWorld& world) {
  droppedAttachments_ = 0;
  for (auto it = attachments_.begin(); it != attachments_.end();) {
    if (it->body == nullptr || isInWorld(world, it->body, it->bodyIndexHint)) {
      ++it;
      continue;
    }
    it = attachments_.erase(it);  // the body may be freed: only the pointer value was used
    ++droppedAttachments_;
    ++warnings_.droppedAttachments;
  }
}

void RopeObject::skipSubstep(const char* reason) {
  rod_.clearLoads();
  pending_.clear();
  contacts_.clear();
  lastStep_ = RopeStepRecord();
  lastStep_.rope = this;
  lastStep_.ok = false;
  lastStep_.failure = reason;
  lastStep_.controlPoints = rod_.controlPointCount();
}

void RopeObject::failSubstep(const char* message) {
  ++warnings_.exceptions;
  lastError_ = message;
  // Without a trial nothing is committed (endSubstep takes the failed branch), so the rod keeps the
  // state it had before the substep. An exception inside the commit itself (adaptivity) leaves the
  // committed positions with the knot changes made so far, each of them exact.
  rod_.clearLoads();
  pending_.clear();
  for (RopeContactRecord& record : contacts_) {
    record.active = false;
    record.force.setZero();
  }
  lastStep_.contacts = 0;
  lastStep_.ok = false;
  lastStep_.failure = "an exception was thrown in the rope's substep; it kept its state (RopeObject::lastError())";
}

void RopeObject::countSubstep() {
  lastStep_.droppedAttachments = droppedAttachments_;
  droppedAttachments_ = 0;
  warnings_.skippedBodies += lastStep_.skippedBodies;
  if (lastStep_.contactsUnsettled) ++warnings_.unsettledContactSteps;
  if (resting_) {
    ++warnings_.restingSubsteps;
  } else if (lastStep_.ok) {
    warnings_.consecutiveFailures = 0;
  } else {
    ++warnings_.failedSteps;
    ++warnings_.consecutiveFailures;
    if (warnings_.consecutiveFailures >= kFailuresBeforeRest) {
      resting_ = true;
      ++warnings_.timesPutToRest;
      rod_.setVelocities(PointList(static_cast<std::size_t>(rod_.controlPointCount()), Vec3::Zero()));
      lastStep_.resting = true;
      lastStep_.failure = kRestingFailure;
    }
  }
}

void RopeObject::wake() {
  resting_ = false;
  warnings_.consecutiveFailures = 0;
}

void RopeObject::restSubstep(const std::vector<const btCollisionObject*>& candidates, double h) {
  rod_.clearLoads();  // loads queued on a resting rope act on nothing
  pending_.clear();
  contacts_.clear();
  lastStep_ = RopeStepRecord();
  lastStep_.rope = this;
  lastStep_.ok = false;
  lastStep_.resting = true;
  lastStep_.failure = kRestingFailure;
  lastStep_.controlPoints = rod_.controlPointCount();
  proxies_->rebuild(rod_);
  OneWayContactLaw law;
  law.friction = settings_.friction;
  std::vector<OneWayContact> pushes;
  std::vector<Contact> found;
  for (const btCollisionObject* object : candidates) {
    btRigidBody* body = dynamicBody(*object);
    if (body == nullptr) continue;  // static and kinematic bodies do not move into a resting rope
    if (!bodyStateFinite(*body)) {
      ++lastStep_.skippedBodies;
      continue;
    }
    btVector3 bodyMin, bodyMax;
    body->getCollisionShape()->getAabb(body->getWorldTransform(), bodyMin, bodyMax);
    pushes.clear();
    const std::size_t firstRecord = contacts_.size();
    // The capsules whose tree leaves meet the body's box, in capsule order.
    std::vector<int> near;
    btNodeStack stack;
    proxies_->capsulesOverlapping(bodyMin, bodyMax, near, stack);
    for (const int i : near) {
      found.clear();
      try {
        findContacts(proxies_->capsule(i), *body, settings_.speculativeMargin, found);
      } catch (const InvalidArgument&) {
        ++lastStep_.skippedBodies;  // a shape the narrowphase does not handle
        break;
      }
      const CapsuleProxy& piece = proxies_->proxy(i);
      for (const Contact& contact : found) {
        OneWayContact push;
        push.contact = contact;  // the rope does not move: ropeVelocity stays zero
        pushes.push_back(push);
        RopeContactRecord record;
        record.rope = this;
        record.body = body;
        record.s = piece.s0 + static_cast<double>(contact.t) * (piece.s1 - piece.s0);
        record.point = contact.pointOnBody;
        record.normal = contact.normal;
        record.depth = -static_cast<double>(contact.distance);
        lastStep_.maxPenetration = std::max(lastStep_.maxPenetration, record.depth);
        contacts_.push_back(record);
      }
    }
    if (pushes.empty()) continue;
    solveOneWayContacts(*body, pushes.data(), static_cast<int>(pushes.size()), h, law);
    for (std::size_t k = 0; k < pushes.size(); ++k) {
      RopeContactRecord& record = contacts_[firstRecord + k];
      record.active = pushes[k].normalImpulse > 0.0;
      record.force = -pushes[k].impulse() / static_cast<btScalar>(h);  // on the rope: the body got the impulse
      if (record.active) ++lastStep_.contacts;
    }
  }
  lastStep_.proxyOverflows = proxies_->updateBoxes(rod_, h, settings_.speculativeMargin);
}

}  // namespace rope::bullet
