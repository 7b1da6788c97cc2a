// SPDX-License-Identifier: MIT
#pragma once
// A winch at one end of a rope (RopeObject::setWinchSpeed / winchTo / payOut): every substep, before
// the rope's step, it pays out (speed > 0) or reels in (speed < 0) speed * h metres of rest length at
// its end (Rod::payOut: the end knots move, a knot enters or leaves at the end, the material and the
// rest of the rope do not change; docs/method.md §16). Whatever holds that end moves with it: a
// point attachment (attachToPoint: a winch fixed in the world, or moved with setAttachmentTarget) or
// a body attachment (attachToBody: a winch on a body), so material leaves or enters the winch point
// at the winch speed. A free end simply grows or shrinks. The tension at the winch is the rope's axial
// force at its end (RopeObject::winchTension, docs/method.md eq. 49).

namespace rope::bullet {

// Which end of a rope (Rod::End): kBegin at rod().beginParameter(), kEnd at rod().endParameter().
enum class RopeEnd { kBegin = 0, kEnd = 1 };

// Fastest winch, m/s of rest length: fast industrial winches reach about 10 m/s.
constexpr double kMaxWinchSpeed = 100.0;

// The state of the winch at one end (RopeObject::winch).
struct Winch {
  double speed = 0.0;          // m/s of rest length, |speed| <= kMaxWinchSpeed: > 0 pays out, < 0 reels in
  double targetLength = -1.0;  // m: the rope's rest length at which the winch stops (winchTo); < 0: none
  bool stalled = false;        // the winch stopped at RopeObject::reelInLimit (reeling in with no target)
  double paidOut = 0.0;        // m of rest length paid out at this end so far (< 0: reeled in)
};

}  // namespace rope::bullet
