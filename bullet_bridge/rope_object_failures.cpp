// RopeObject: attachments that would break the rope are refused; what a RopeWorld does when a rope's
// substep cannot run or goes wrong (rope_warnings.h; nothing there throws, it runs inside Bullet's
// stepSimulation).
#include <algorithm>

#include "bullet_bridge/rope_object.h"
#include "bullet_bridge/world_membership.h"
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
  if (lastStep_.ok) {
    warnings_.consecutiveFailures = 0;
  } else {
    ++warnings_.failedSteps;
    ++warnings_.consecutiveFailures;
  }
}

}  // namespace rope::bullet
