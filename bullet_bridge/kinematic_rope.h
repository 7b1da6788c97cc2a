// SPDX-License-Identifier: MIT
#pragma once
// A kinematic tractrix rope in a Bullet world ([B]'s "follow the leader": cables dragged by robots,
// hoses, tails): a rope::TractrixRope whose leading end follows a rigid body's point, a fixed target
// or a scripted path, stepped once per Bullet internal substep by its own btActionInterface.
//
//   rope::bullet::KinematicRope hose(rope::TractrixRope(shape, tractrixSettings));
//   hose.addToWorld(dynamicsWorld);                         // any btDiscreteDynamicsWorld
//   hose.followBodyPoint(gripper, btVector3(0, 0, -0.05));  // or setTarget(p) / followPath(f)
//   dynamicsWorld.stepSimulation(1.0 / 60, 4, 1.0 / 240);  // the rope moves inside each substep
//   hose.removeFromWorld();                                 // also done by the destructor
//
// Its collision geometry is a chain of capsules over its spline (capsulesPerSpan per knot span) in
// one Bullet collision object, of the same type as a dynamic rope's (capsule_proxies.h): a compound of
// the capsules whose tree leaves are swept boxes (each capsule at the start and at the end of the
// substep, padded), one broadphase box for the whole rope. Its userIndex2 is kKinematicRopeTag. It
// carries CF_NO_CONTACT_RESPONSE and asks Bullet for no pair except with dynamic ropes, so Bullet's
// solver and narrowphase never act on it; Bullet's own queries (rayTest, contactTest,
// contactPairTest, convexSweepTest) see its capsules like any compound's, as exact capsules whether
// or not the world has a RopeWorld (collision_object/capsule_dispatch.h), and ropeHit
// (rope_queries.h) maps such a hit to the rope and the curve parameter s. After moving, the rope
// finds the dynamic bodies overlapping its capsules through the broadphase, measures contacts with
// the bridge's narrowphase (find_contacts.h) and pushes each body by one-way contact impulses, all
// contacts of a body solved together (contact/kinematic_push.h). Nothing acts on the rope: static and
// kinematic objects, the body it follows and other kinematic ropes are passed through.
//
// Dynamic ropes (RopeObject in a RopeWorld of the same world) are pushed one way too: their RopeWorld
// takes the kinematic rope's object as a moving body (find_contacts.h: capsule against its capsules;
// the surface moves at surfaceVelocity), so a dynamic rope gets the same line contact, stick and
// Coulomb friction as against any kinematic body (friction: the rope's coefficient times the
// object's Bullet default 0.5, friction_combination.h), and the kinematic rope feels nothing. The
// pair obeys both ropes' collision group and mask, as any Bullet pair.
//
// Bullet's debugDrawWorld() draws the rope's centre line (the capsule axes) through btIDebugDraw.
//
// Timing: Bullet runs actions after a substep's integration; the rope moves to the driver's position
// for the end of that substep, and the impulses set the bodies' velocities for the next one.
//
// Failures: nothing is thrown out of stepSimulation. A substep with a time step that is not finite and
// > 0 is skipped; an exception from the followPath function or from the rope's own code is caught; the
// rope then holds where it is, lastStep() says why and warnings() counts it (rope_warnings.h).
//
// Lifetime: remove the rope from its world (removeFromWorld, or destroy it) before the Bullet world
// is destroyed, as for every object a Bullet world holds. If the world is destroyed first anyway,
// removeFromWorld notices it (Bullet's world destructor clears the broadphase handle of the rope's
// object) and leaves the dead world alone.

#include <BulletDynamics/Dynamics/btActionInterface.h>
#include <BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/capsule.h"
#include "bullet_bridge/capsule_proxies.h"
#include "bullet_bridge/contact.h"
#include "bullet_bridge/contact/kinematic_push.h"
#include "bullet_bridge/kinematic_rope_settings.h"
#include "bullet_bridge/rope_warnings.h"
#include "rope/tractrix/tractrix_rope.h"

namespace rope::bullet {

class CapsuleDispatch;  // collision_object/capsule_dispatch.h (internal)

// One push of the last substep.
struct KinematicContactRecord {
  const btCollisionObject* body = nullptr;
  int capsule = 0;                 // capsule index along the rope (0 at the leading end)
  double s = 0.0;                  // curve parameter of the contact on the rope
  btVector3 point{0, 0, 0};        // on the body surface, world frame, m
  btVector3 normal{0, 0, 1};       // unit, from the body into the rope
  double depth = 0.0;              // m, > 0 penetrating, < 0 speculative gap
  btVector3 impulse{0, 0, 0};      // given to the body, N s (zero if it already moved away fast enough)
};

struct KinematicRopeStepReport {
  long substep = 0;         // substeps taken since addToWorld
  double time = 0.0;        // s, simulated time since addToWorld (what followPath's function gets)
  double timeStep = 0.0;    // s, the last substep
  // Why the leading end did not move to the driver's position this substep: nullptr if it did (or
  // holds still by choice). A target that is not finite or beyond kMaxTractrixCoordinate, a followed
  // body that left the world: the rope then holds where it is (an exception cannot leave a substep).
  const char* targetFailure = nullptr;
  // Why the substep did not run or stopped part-way (static text), nullptr if it ran: a time step
  // that is not finite and > 0, or an exception caught in the rope's code (KinematicRope::lastError()).
  const char* failure = nullptr;
  // Bodies passed through: a shape the narrowphase does not support (find_contacts.h), or a
  // non-finite transform or velocity.
  int unsupportedBodies = 0;
  // Capsule boxes Bullet would drop as too large (diagonal^2 >= 1e12 m^2); the previous box is kept.
  int oversizedBoxes = 0;
  double maxPenetration = 0.0;        // m, deepest body penetration found this substep (before the push)
  btVector3 totalImpulse{0, 0, 0};    // N s, sum of all impulses given this substep
  std::vector<KinematicContactRecord> contacts;
};

class KinematicRope {
 public:
  // Throws InvalidArgument naming the settings field (settings.validate()). The leading end holds
  // still until a driver is set.
  explicit KinematicRope(TractrixRope rope, const KinematicRopeSettings& settings = {});
  ~KinematicRope();  // leaves its world first (so destroy it, or removeFromWorld, before the world)
  KinematicRope(const KinematicRope&) = delete;
  KinematicRope& operator=(const KinematicRope&) = delete;

  // Registers the action and the capsules ("world": already in a world). removeFromWorld undoes it
  // (no-op when not in a world); the rope keeps its state and may be added again.
  void addToWorld(btDiscreteDynamicsWorld& world);
  void removeFromWorld();
  btDiscreteDynamicsWorld* world() const { return world_; }

  // Drivers; each replaces the previous one and takes effect at the next substep (the leading end
  // moves there in a straight line, as TractrixRope::moveLeadingEnd). All throw InvalidArgument and
  // leave the rope and its driver unchanged on bad input.
  // The body's point localPoint (centre-of-mass frame, m), read after each substep's integration.
  // The body itself is never pushed by this rope. "body" for nullptr, "localPoint.x|y|z" if not finite.
  // While the body is not among the world's collision objects (checked by pointer, never
  // dereferenced, so it may have been removed and deleted) the rope holds and reports it.
  void followBodyPoint(btRigidBody* body, const btVector3& localPoint);
  // A fixed world point ("target.x|y|z": not finite or beyond kMaxTractrixCoordinate). The rope gets
  // there within one substep, so a distant target is a fast sweep (and bodies it hits get that
  // speed); move it in small steps, or use followPath, for a smooth motion.
  void setTarget(const btVector3& target);
  // position(t) for the simulated time t since addToWorld (s), evaluated at the end of each substep.
  // "path" for an empty function. A non-finite position, or an exception thrown by the function
  // (caught: warnings().pathExceptions, lastError()), makes the rope hold (report.targetFailure).
  void followPath(std::function<btVector3(double)> path);
  // The leading end stays where it is.
  void hold();
  const btRigidBody* followedBody() const { return body_; }

  const TractrixRope& tractrix() const { return rope_; }
  const KinematicRopeSettings& settings() const { return settings_; }
  const KinematicRopeStepReport& lastStep() const { return report_; }
  // Warnings counted since the rope was created (rope_warnings.h), and the message of the last
  // exception caught in a substep ("" if none).
  const KinematicRopeWarnings& warnings() const { return warnings_; }
  const std::string& lastError() const { return lastError_; }
  btVector3 leadingEnd() const;

  // Capsules at the last substep (or at addToWorld), leading end first.
  int capsuleCount() const { return proxies_.size(); }
  Capsule capsule(int i) const;                              // "i" out of range
  // The curve parameters of capsule i's two ends (its axis runs from C(first) to C(second)).
  std::pair<double, double> capsuleParameters(int i) const;  // "i" out of range
  // The rope's one collision object (compound child i = capsule i) and its capsule chain.
  const btCollisionObject& collisionObject() const { return proxies_.object(); }
  const CapsuleProxies& proxies() const { return proxies_; }
  // The kinematic rope a collision object stands in for, or nullptr.
  static KinematicRope* ropeOf(const btCollisionObject& object);
  // Velocity (m/s) of the rope's surface at `point` near capsule i over the last substep: the capsule's
  // end points' motion over that substep, interpolated at the point's projection on the axis. Zero
  // before the first substep and after one that did not move the rope (skipped, or failed). What a dynamic rope touching this rope sees as the other side's velocity.
  btVector3 surfaceVelocity(int i, const btVector3& point) const;  // "i" out of range, "point.x|y|z" not finite

 private:
  class Action;
  struct Candidate {
    int worldIndex;
    int capsule;
    btRigidBody* body;
  };

  void substep(double h);
  void moveAndPush(double h);
  void recoverFromException(const char* message) noexcept;
  bool driverTarget(Vec3& target);       // false: hold (report_.targetFailure says why, if it failed)
  void rebuildCapsules(bool swept);      // parameters, axis points and boxes from the current curve
  void findCandidates();
  void push(double h);

  TractrixRope rope_;
  KinematicRopeSettings settings_;
  std::unique_ptr<Action> action_;
  btDiscreteDynamicsWorld* world_ = nullptr;

  enum class Driver { kHold, kTarget, kBody, kPath };
  Driver driver_ = Driver::kHold;
  Vec3 target_ = Vec3::Zero();
  btRigidBody* body_ = nullptr;
  int bodyIndexHint_ = -1;  // where body_ was last seen in the world's object array (detail/world_membership.h)
  btVector3 localPoint_{0, 0, 0};
  std::function<btVector3(double)> path_;
  double time_ = 0.0;
  double moveStep_ = 0.0;  // s: the last substep's time step if the capsules moved in it, else 0

  // The curve before this substep's move, to measure how far each capsule end moved.
  KnotVector previousKnots_;
  PointList previousPoints_;

  std::vector<double> ends_;              // capsule end parameters, capsuleCount() + 1
  std::vector<btVector3> axis_;           // capsule end points now
  std::vector<btVector3> previousAxis_;   // the same parameters on the previous curve
  std::vector<btScalar> bulge_;           // per capsule: the curve's distance from its chord midpoint
  // Bullet's queries meet the capsules exactly, with or without a RopeWorld; held while in a world.
  std::shared_ptr<CapsuleDispatch> capsuleDispatch_;
  CapsuleProxies proxies_;  // the collision object: leaves are the capsules' boxes over the last substep
  std::vector<Candidate> candidates_;
  std::vector<Contact> scratch_;
  std::vector<OneWayContact> bodyContacts_;
  KinematicRopeStepReport report_;
  KinematicRopeWarnings warnings_;
  std::string lastError_;
};

}  // namespace rope::bullet
