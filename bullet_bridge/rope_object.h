// SPDX-License-Identifier: MIT
#pragma once
// A rope as a Bullet world object: owns a rope::Rod, its capsule proxies (capsule_proxies.h), its
// attachments (attachment.h) and the contacts of its last substep. The user owns it; a RopeWorld
// (rope_world.h) adds it to a Bullet world and steps it inside Bullet's substeps.
//
//   rope::bullet::RopeWorld ropes(dynamicsWorld);           // once per btDiscreteDynamicsWorld
//   rope::bullet::RopeObject rope(rope::Rod::fromSegment(rodSettings, a, b));
//   ropes.addRope(rope);
//   rope.attachToBody(rope.rod().endParameter(), *box, btVector3(0, 0.1, 0));
//   dynamicsWorld.stepSimulation(1.0 / 60.0, 4, 1.0 / 240.0);
//   ropes.removeRope(rope);
//
// The rope's material and discretisation come from its RodSettings; its gravity from the Bullet world
// it is in (every substep, BulletRopeSettings::gravitySource / gravityScale). Between steps the rod
// may be read freely; change it (pins, setControlPoints, ...) only
// through rod() while no stepSimulation runs.

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "bullet_bridge/attachment.h"
#include "bullet_bridge/contact/body_contacts.h"
#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/capsule_proxies.h"
#include "bullet_bridge/contact.h"
#include "bullet_bridge/contact_report.h"
#include "bullet_bridge/friction_combination.h"
#include "bullet_bridge/rope_settings.h"
#include "bullet_bridge/rope_warnings.h"
#include "bullet_bridge/winch.h"
#include "rope/rod/rod.h"

namespace rope::bullet {

class RopeWorld;

class RopeObject {
 public:
  // Throws InvalidArgument naming the settings field (settings.validate()).
  explicit RopeObject(Rod rod, const BulletRopeSettings& settings = {});
  // Leaves its world first if it is still in one.
  ~RopeObject();
  RopeObject(const RopeObject&) = delete;
  RopeObject& operator=(const RopeObject&) = delete;

  Rod& rod() { return rod_; }
  const Rod& rod() const { return rod_; }
  const BulletRopeSettings& settings() const { return settings_; }
  RopeWorld* world() const { return world_; }
  const CapsuleProxies& proxies() const { return *proxies_; }
  // The rope's one collision object in the Bullet world (capsule_proxies.h): Bullet's queries report
  // hits on it (rope_queries.h: ropeHit gives the rope and s of a hit).
  const btCollisionObject& collisionObject() const { return proxies_->object(); }
  // New broadphase filter (settings().collisionGroup / collisionMask), in effect from the next
  // collision detection on. Throws InvalidArgument naming "group" (0: no bit set), or "rope" while its
  // RopeWorld is in a substep (from a substep callback: the dispatch is under way), and changes nothing.
  void setCollisionFilter(int group, int mask);

  // ---- attachments (ids are unique per rope) ----
  // C(s) to the body's point `localPoint` (centre-of-mass frame). Throws InvalidArgument for s
  // outside the rope or NaN ("s"), a non-finite localPoint ("localPoint"), bad settings
  // ("attachment.*"), a rope in no world ("rope"), a body not in the rope's world ("body"), or the
  // same body already attached within RodSettings::minKnotSpacing (rest length) of s ("s": a second
  // spring at one point only stiffens the first beyond its stability cap; change its settings).
  int attachToBody(double s, btRigidBody& body, const btVector3& localPoint, const AttachmentSettings& settings = {});
  // A clamp (weld) to a body: C(s) held at the body's point localPoint like attachToBody, and the
  // rope's tangent at s held along localDirection (body frame, any length > 0), two-way: the body
  // receives the force and the moment (attachment.h). Removable with removeAttachment. Throws like
  // attachToBody, and for a non-finite ("localDirection.x", ...) or zero ("localDirection")
  // direction or bad angular settings ("attachment.angularStiffness", ...).
  int clampToBody(double s, btRigidBody& body, const btVector3& localPoint, const btVector3& localDirection,
                  const AttachmentSettings& settings = {});
  // C(s) held at a world point (a rod pin); move it with setAttachmentTarget. Throws for a bad s
  // ("s"), a non-finite point ("point") or a pin already at s.
  int attachToPoint(double s, const btVector3& point);
  // New target of a point attachment, reached at the end of the next substep (moving target).
  // Throws for an unknown id or a body attachment ("id") or a non-finite point ("point").
  void setAttachmentTarget(int id, const btVector3& point);
  // Throws for an unknown id ("id").
  void removeAttachment(int id);
  const std::vector<Attachment>& attachments() const { return attachments_; }

  // ---- loads ----
  // A force (N) or impulse (N s) at C(s), world frame, acting in the next substep only, like the rod's
  // own loads (Rod::addForce / addImpulse, which work here too: a substep takes every load queued on
  // rod() and clears them). A force that lasts is applied again before every substep, e.g. from
  // RopeWorld::setSubstepCallback, which runs after each one. Throws InvalidArgument naming "s" or
  // "force[i]" / "impulse[i]" and queues nothing.
  void applyForce(double s, const btVector3& force);
  void applyImpulse(double s, const btVector3& impulse);
  // A force per metre of rope (N/m of rest length, world frame) over [s0, s1], acting in the next
  // substep only like applyForce: integrated along the rope by Gauss-Legendre into the consistent
  // generalised forces (contact/distributed_loads.h), so a uniform q over the whole rope moves its centre of
  // mass exactly like a force q * restLength. Throws InvalidArgument naming "s0" / "s1" (NaN, outside
  // the rope, s1 <= s0) or "forcePerLength[i]" (not finite) and queues nothing.
  void applyDistributedForce(double s0, double s1, const btVector3& forcePerLength);

  // ---- tension ----
  // The axial force in the rope at s, N (> 0 pulling, < 0 compressed): the material's elastic
  // force from the stretching law (docs/method.md §6), T = (EA/2) (g^2 - 1) g with g the stretch, as
  // the rod's stretching quadrature samples it (rope::axialForce, rope/rod/axial_force.h: interpolated
  // between the sample points, so the readout carries exactly what the rod's forces carry), at the
  // rope's current state. Throws InvalidArgument("s", ...) for s outside the rope or NaN.
  double tension(double s) const;
  // The tension at an attachment (at its s). Throws InvalidArgument("id", ...) for an unknown id.
  double attachmentTension(int id) const;
  // Every attachment's load after the last substep (also in RopeWorld::lastReport().attachments).
  const std::vector<RopeAttachmentRecord>& attachmentLoads() const { return attachmentLoads_; }

  // ---- winch (winch.h; docs/method.md §16) ----
  // Pays out (length > 0) or reels in (< 0) `length` m of rest length at `end` now (Rod::payOut);
  // attachments at that end move with it. Throws InvalidArgument naming "end", "length" (not finite,
  // or more than reelInLimit(end)) and changes nothing.
  void payOut(RopeEnd end, double length);
  // A winch that runs from the next substep on at `speed` m/s of rest length (> 0 pays out, < 0
  // reels in, 0 stops), until stopped or, reeling in, until reelInLimit (Winch::stalled). Throws
  // InvalidArgument naming "end" or "speed" (not finite or |speed| > kMaxWinchSpeed).
  void setWinchSpeed(RopeEnd end, double speed);
  // A winch that runs at `speed` (> 0, <= kMaxWinchSpeed) until the rope's rest length is
  // `restLength` (m), paying out or reeling in as needed, and stops there exactly. Throws
  // InvalidArgument naming "end", "speed", or "restLength" (not finite, or shorter than reelInLimit
  // allows) and changes nothing.
  void winchTo(RopeEnd end, double restLength, double speed);
  const Winch& winch(RopeEnd end) const;
  // The tension at the winch: the rope's axial force at its end (tension(s) at that end), N.
  double winchTension(RopeEnd end) const;
  // How much rest length can be reeled in at `end` (m): the rope keeps Rod::minimumRestLength() and
  // RodSettings::minKnotSpacing from every pin, clamp, attachment and queued load not at that end.
  // Exactly 0 within rounding (1e-12 of the rest length): a winch that stalled there reads 0.
  double reelInLimit(RopeEnd end) const;

  // ---- cutting ([A] §5.1) ----
  // Cuts the rope at s (Rod::cutPoint: on a knot within minKnotSpacing of s; no piece shorter than
  // that; not exactly at a pin or a body attachment): this object keeps
  // [beginParameter, s] and the returned one is [s, endParameter] (Rod::cut: the two pieces share no
  // basis function, so no mass, energy or force term). Positions, velocities, rest state, pins and
  // attachments go to the piece they lie on; attachment ids are kept. The winch at the end goes with
  // the new piece (a winchTo target less the rest length this object keeps, and the other way
  // round). If this rope is in a world, the new piece is added to it with the same settings, its own
  // capsules and contacts. The two cut ends start where they were, overlapping: until they part,
  // contact between the pieces within
  // selfContactExclusion of the cut is excluded as if they were still one rope. Throws
  // InvalidArgument ("s") and changes nothing for a bad s. The caller owns the new piece.
  std::unique_ptr<RopeObject> cut(double s);
  // The pieces this rope was cut from or into, with the cut's parameter on each (exclusion above).
  struct CutPartner {
    const RopeObject* rope = nullptr;
    double ownEnd = 0.0;      // parameter of the cut end on this rope
    double partnerEnd = 0.0;  // parameter of the cut end on the partner
  };
  const std::vector<CutPartner>& cutPartners() const { return cutPartners_; }

  // ---- last substep ----
  // Rope-body contacts of the last substep: one record per quadrature sample of the line contact
  // (contact/body_contacts.h), its force the sample's share of the pressure over the substep.
  const std::vector<RopeContactRecord>& contacts() const { return contacts_; }
  const RopeStepRecord& lastStep() const { return lastStep_; }
  // What went wrong in this rope's substeps since it was created (rope_warnings.h; a RopeWorld counts
  // them), and the message of the last exception caught in one of them ("" if none).
  const RopeWarnings& warnings() const { return warnings_; }
  const std::string& lastError() const { return lastError_; }

  // Solves of one substep's contact active set (release pulling samples, slide sticking ones beyond
  // mu f_n, re-bound sliding ones); the last is kept, and flagged if it still wanted a change
  // (lastStep().contactsUnsettled). Ten, not six: with the default material damping a slip front
  // round a drum wound twice at mu = 1 and 0.9 of the capstan limit needed more than six in 28 of 240
  // substeps (6 with ten); a step that settles sooner stops sooner.
  static constexpr int kMaxContactSolvePasses = 10;

  // ---- a rope that keeps failing ----
  // After this many failed substeps in a row (one simulated second at 240 Hz) a RopeWorld puts the
  // rope to rest: its velocities are set to zero and it no longer steps, so a rope that cannot be
  // solved (settings far outside their range, an impossible constraint) costs no more solves and
  // cannot go wrong, while the world goes on. It stays in the world as a fixed obstacle: bodies still
  // collide with it (one-way contact, as against a kinematic rope: contact/kinematic_push.h), its capsules
  // stay in the broadphase for queries, and other ropes see it as they see a rope whose step failed.
  // Each resting substep reports lastStep().ok == false, lastStep().resting == true and the failure
  // text below, and counts warnings().restingSubsteps; warnings().timesPutToRest counts the events.
  // wake() lets it try again (from its resting state, at rest).
  static constexpr int kFailuresBeforeRest = 240;
  static constexpr const char* kRestingFailure =
      "the rope failed RopeObject::kFailuresBeforeRest substeps in a row and is at rest (frozen, still colliding)";
  bool resting() const { return resting_; }
  void wake();

  // One substep of h seconds against the candidate bodies (sorted, deterministic order), on its own:
  // beginSubstep then endSubstep. RopeWorld's action calls the two halves itself, after Bullet's
  // collision detection, solver and integration of the substep, with rope-rope contact in between.
  // Throws InvalidArgument("h", ...) for h not finite and > 0 before changing anything. Called
  // directly, these may throw; inside a RopeWorld every exception is caught and counted (warnings()).
  void substep(const std::vector<const btCollisionObject*>& candidates, double h);
  // Rope-body contacts and attachments, and the rod's trial step with them (Rod::solveTrial; the
  // rod's state is unchanged). lastStep().ok is false if the trial failed.
  void beginSubstep(const std::vector<const btCollisionObject*>& candidates, double h);
  // Commits the (possibly corrected) trial, applies the opposite impulses to the bodies, records the
  // contact forces and refreshes the swept capsule boxes.
  void endSubstep(double h);

 private:
  friend class RopeWorld;
  // endSubstep, except that the rope's new box reaches Bullet's broadphase only at announceBox()
  // (CapsuleProxies::updateBoxesDeferred): the RopeWorld hands the boxes over in world order.
  void finishSubstep(double h);
  void announceBox();
  // beginSubstep in two halves, so that the RopeWorld can find rope-rope contacts between them, on
  // another thread (rope_world.cpp): prepareSubstep runs the winches, queues the loads and rebuilds
  // the capsules (after it, the capsules and the rod's state before the step are what rope-rope
  // contact reads, and solveSubstepTrial changes neither); solveSubstepTrial finds the body
  // contacts and solves the trial.
  void prepareSubstep(double h);
  void solveSubstepTrial(const std::vector<const btCollisionObject*>& candidates, double h);
  // Whether finishing this substep (endSubstep) acts on nothing but this rope: no attachment spring
  // and no contact sample gives a dynamic body an impulse. Such a rope's substep can be finished
  // before the other ropes' begin without changing what they see.
  bool finishesAlone() const;
  // What a substep works in and nothing carries to the next (the contact samples, the rod's system,
  // force lists, trial and queued springs' buffer): RopeWorld lends one set to each rope it steps
  // (swapStepScratch before beginSubstep, and again after finishSubstep if that came within the
  // rope's visit), so that a thousand ropes write their substeps into one set, still in the caches.
  // Results are bit for bit those of the rope's own storage. Not with a trial pending (Rod).
  struct StepScratch {
    BodyContacts::Scratch contacts;
    Rod::StepScratch rod;
  };
  void swapStepScratch(StepScratch& scratch) {
    rod_.swapStepScratch(scratch.rod);  // first: it throws, with nothing changed, if a trial is pending
    bodyContacts_.swapScratch(scratch.contacts);
  }
  // Cache hints (rope/common/prefetch.h) the RopeWorld gives three, two and one ropes ahead of the
  // rope it steps: this object's own bytes; then (once they have arrived) its capsule proxies'
  // object; then the heap blocks both point to. Each stage reads only pointers the previous one
  // brought in, so none of them waits for memory.
  void prefetchObject() const;
  void prefetchParts() const;
  // prefetchState: what lasts from one substep to the next (a rope about to be lent the step's
  // storage, swapStepScratch); prefetchTrial: that and the storage the rope holds now (one that has
  // begun its substep and still has to finish it).
  void prefetchState() const;
  void prefetchTrial() const;
  void prefetchContactState() const;  // both's part beyond the rod: capsules, contacts, attachments
  // The same for what RopeWorld's last pass over the ropes reads once the rope's substep is done:
  // its records and its collision object (the box for Bullet's broadphase).
  void prefetchRecords() const;
  // Rope-rope contact statistics of the substep (RopeWorld fills them in between the two halves).
  // `near`: the rope had rope-rope or self-contact candidates (active or not) this substep.
  void recordRopeContacts(int active, double maxOverlap, bool near) {
    lastStep_.ropeContacts = active;
    lastStep_.maxSelfOverlap = maxOverlap;
    nearRopes_ = near;
    if (near) rod_.markContact();
  }
  void shareBodyAttachmentCounts(const std::vector<std::pair<const btRigidBody*, int>>* counts) {
    bodyAttachmentCounts_ = counts;
  }
  void enterWorld(RopeWorld& world, btCollisionWorld& collisionWorld);
  void leaveWorld();
  // ---- failure handling inside a RopeWorld substep (rope_object_failures.cpp) ----
  // Drops the body attachments whose body is no longer among world's collision objects (compared by
  // pointer, never dereferenced: the body may have been deleted).
  void dropDepartedAttachments(const btCollisionWorld& world);
  // The substep is not run (reason: static text); the rope keeps its state.
  void skipSubstep(const char* reason);
  // An exception (message) was caught in this rope's substep: drops the trial and the queued loads so
  // the rope keeps its last good state, and deactivates the substep's contacts.
  void failSubstep(const char* message);
  // Adds the substep's outcome to warnings_ (called once per substep, after endSubstep or skipSubstep)
  // and puts the rope to rest after kFailuresBeforeRest failures in a row.
  void countSubstep();
  // A substep at rest: the rope does not move; dynamic bodies touching it are pushed out of it
  // (one-way contact with the rope's friction), the contacts recorded as usual.
  void restSubstep(const std::vector<const btCollisionObject*>& candidates, double h);
  int findAttachment(int id) const;
  // winch.cpp: the parameter of an end; the end moved with its attachments; the winches' substep.
  double endParameter(RopeEnd end) const;
  void moveRopeEnd(RopeEnd end, double length);
  void runWinches(double h);
  void requireNewBodyPoint(double s, const btRigidBody& body) const;  // rope_object_failures.cpp
  // The springs of the body attachments for this substep (pending_), capped on light bodies.
  void queueAttachments(double h);
  // A clamp's rotational spring (attachment.h), capped on a light body.
  void queueClampTangent(const Attachment& attachment, btRigidBody& body, int index, double h);
  // The rod's trial step with the attachments and the body contacts' active set (contact/body_contacts.h).
  StepReport solveTrialWithContacts(double h);
  void queueTrialLoads();  // the user's loads, attachments' springs and contact samples, on a cleared rod
  // Whether the rope is attached to object within 4 radii of the capsule [s0, s1]: the rope's end sits
  // in the body's surface there, so those contacts are ignored.
  bool attachedNear(const btCollisionObject& object, double s0, double s1) const;
  // The friction coefficient of this rope against body (friction_combination.h).
  double bodyFriction(const btCollisionObject& body) const;
  // An attachment's spring, queued on the rod with every solve of the substep.
  struct PendingSpring {
    double s;
    Vec3 velocity;      // rope velocity at s before the step (tangent springs: Cdot'(s))
    Vec3 derivative;    // tangent springs: C'(s) before the step
    bool tangent;       // a clamp's rotational spring (Rod::addTangentSpring)
    ContactSpring spring;
    btRigidBody* body;  // receives the opposite impulse (nullptr: static or kinematic)
    btVector3 point;    // where, world frame
    int attachment;     // index in attachments_
  };

  Rod rod_;
  BulletRopeSettings settings_;
  std::vector<CutPartner> cutPartners_;
  int worldIndex_ = -1;  // position in its RopeWorld's ropes(), -1 outside a world
  std::unique_ptr<CapsuleProxies> proxies_;
  RopeWorld* world_ = nullptr;
  std::vector<Attachment> attachments_;
  int nextAttachmentId_ = 1;
  std::vector<RopeContactRecord> contacts_;
  std::vector<RopeAttachmentRecord> attachmentLoads_;
  RopeStepRecord lastStep_;
  // How many body attachments (of all ropes in the RopeWorld) pull on each body, sorted by body; set
  // by the RopeWorld each substep (empty: count this rope's own). seriesWithBody takes the body's
  // response N times as large for N attachments, so parallel ropes on one body do not overshoot.
  const std::vector<std::pair<const btRigidBody*, int>>* bodyAttachmentCounts_ = nullptr;
  int attachmentsOn(const btRigidBody* body) const;
  bool nearRopes_ = false;  // rope-rope candidates last substep: the next one restarts BDF2
  bool nearRopesBefore_ = false;  // nearRopes_ as prepareSubstep found it, for solveSubstepTrial
  std::chrono::steady_clock::time_point substepStart_;  // prepareSubstep's rebuild began (contactSeconds)
  std::vector<PendingSpring> pending_;
  Rod::LoadQueue userLoads_;  // what the user queued on the rod for this substep
  BodyContacts bodyContacts_;
  RopeWarnings warnings_;
  std::string lastError_;
  int droppedAttachments_ = 0;  // by dropDepartedAttachments in the current substep
  Winch winches_[2];            // at kBegin, kEnd
  bool resting_ = false;        // put to rest (kFailuresBeforeRest)
};

}  // namespace rope::bullet
