// SPDX-License-Identifier: MIT
// RopeObject's winches (winch.h; docs/method.md §16).
#include <algorithm>
#include <cmath>
#include <string>

#include "bullet_bridge/rope_object.h"
#include "rope/common/error.h"
#include "rope/spline/arc_length.h"

namespace rope::bullet {

namespace {

Rod::End rodEnd(RopeEnd end) { return end == RopeEnd::kBegin ? Rod::End::kBegin : Rod::End::kEnd; }

void requireEnd(RopeEnd end) {
  if (end != RopeEnd::kBegin && end != RopeEnd::kEnd) {
    throw InvalidArgument("end", std::to_string(static_cast<int>(end)), "is not a RopeEnd");
  }
}

void requireSpeed(double speed) {
  requireFinite("speed", speed);
  if (!(std::abs(speed) <= kMaxWinchSpeed)) {
    throw InvalidArgument("speed", formatValue(speed), "must be within +-" + formatValue(kMaxWinchSpeed) + " m/s");
  }
}

}  // namespace

double RopeObject::endParameter(RopeEnd end) const {
  return end == RopeEnd::kBegin ? rod_.beginParameter() : rod_.endParameter();
}

double RopeObject::reelInLimit(RopeEnd end) const {
  requireEnd(end);
  // The rod's own limit (minimum length, pins, queued loads) and the body attachments away from the end.
  double limit = rod_.reelInLimit(rodEnd(end));
  const double at = endParameter(end);
  for (const Attachment& attachment : attachments_) {
    if (attachment.body == nullptr || attachment.s == at) continue;
    const double distance = arcLength(rod_.knots(), rod_.restControlPoints(), std::min(at, attachment.s),
                                      std::max(at, attachment.s));
    limit = std::min(limit, distance - rod_.settings().minKnotSpacing);
  }
  return limit > 1e-12 * rod_.restLength() ? limit : 0.0;  // as Rod::reelInLimit: rounding is zero
}

void RopeObject::moveRopeEnd(RopeEnd end, double length) {
  const double oldEnd = endParameter(end);
  rod_.payOut(rodEnd(end), length);  // moves the rod's pins at the end with it
  const double newEnd = endParameter(end);
  for (Attachment& attachment : attachments_) {
    if (attachment.s == oldEnd) attachment.s = newEnd;
  }
  winches_[static_cast<int>(end)].paidOut += length;
}

void RopeObject::payOut(RopeEnd end, double length) {
  requireEnd(end);
  requireFinite("length", length);
  if (length < 0.0) {
    const double limit = reelInLimit(end);
    if (-length > limit + 1e-12 * rod_.restLength()) {
      throw InvalidArgument("length", formatValue(length),
                            "reels in more than the " + formatValue(limit) +
                                " m this end allows (minimum rest length, and RodSettings::minKnotSpacing from "
                                "every pin, clamp, attachment and queued load)");
    }
  }
  moveRopeEnd(end, length);
  proxies_->updateBoxes(rod_, settings_.initialPredictionTime, settings_.speculativeMargin);
}

void RopeObject::setWinchSpeed(RopeEnd end, double speed) {
  requireEnd(end);
  requireSpeed(speed);
  Winch& winch = winches_[static_cast<int>(end)];
  winch.speed = speed;
  winch.targetLength = -1.0;
  winch.stalled = false;
}

void RopeObject::winchTo(RopeEnd end, double restLength, double speed) {
  requireEnd(end);
  requireFinite("restLength", restLength);
  requireSpeed(speed);
  if (!(speed > 0.0)) throw InvalidArgument("speed", formatValue(speed), "must be > 0");
  const double current = rod_.restLength();
  if (restLength < current) {
    const double limit = reelInLimit(end);
    if (current - restLength > limit + 1e-12 * current) {
      throw InvalidArgument("restLength", formatValue(restLength),
                            "would reel in " + formatValue(current - restLength) + " m, more than the " +
                                formatValue(limit) +
                                " m this end allows (minimum rest length, and RodSettings::minKnotSpacing from "
                                "every pin, clamp, attachment and queued load)");
    }
  }
  Winch& winch = winches_[static_cast<int>(end)];
  winch.speed = restLength >= current ? speed : -speed;
  winch.targetLength = restLength;
  winch.stalled = false;
}

const Winch& RopeObject::winch(RopeEnd end) const {
  requireEnd(end);
  return winches_[static_cast<int>(end)];
}

double RopeObject::winchTension(RopeEnd end) const {
  requireEnd(end);
  return tension(endParameter(end));
}

void RopeObject::runWinches(double h) {
  for (RopeEnd end : {RopeEnd::kBegin, RopeEnd::kEnd}) {
    Winch& winch = winches_[static_cast<int>(end)];
    if (winch.speed == 0.0) continue;
    double length = winch.speed * h;
    if (winch.targetLength >= 0.0) {
      const double toGo = winch.targetLength - rod_.restLength();
      if (std::abs(toGo) <= std::abs(length)) {  // arrives in this substep
        length = toGo;
        winch.speed = 0.0;
        winch.targetLength = -1.0;
      }
    }
    if (length < 0.0) {
      // Something moved into the way since the command (a new attachment, a load): stop there.
      const double limit = reelInLimit(end);
      if (-length > limit) {
        length = -limit;
        winch.speed = 0.0;
        winch.targetLength = -1.0;
        winch.stalled = true;
      }
    }
    if (length != 0.0) moveRopeEnd(end, length);
  }
}

}  // namespace rope::bullet
