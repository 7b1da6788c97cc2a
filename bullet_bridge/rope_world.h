// SPDX-License-Identifier: MIT
#pragma once
// Ropes in a user's Bullet world. A RopeWorld wraps one btDiscreteDynamicsWorld (or a subclass such
// as btSoftRigidDynamicsWorld) and installs one btActionInterface in it, so every rope steps once per
// Bullet internal substep with Bullet's fixed step, right after that substep's collision detection,
// constraint solve and integration (stepSimulation(dt, maxSubSteps, fixedStep) works unchanged).
// Each rope is one collision object in the Bullet world (capsule_proxies.h): Bullet's broadphase sees
// one box per rope and its dispatcher hands each of the rope's pairs to the RopeWorld (collision_object/rope_dispatch.h,
// which the RopeWorld installs on the world's btCollisionDispatcher). In each substep the RopeWorld
// reads those pairs (re-checking the overlap: Bullet drops pairs lazily), finds the capsules involved in the ropes' trees (rope against a body's box, tree
// against tree for rope-rope and self-contact), runs the bridge's narrowphase, applies the contact
// and attachment response (contact/contact_response.h, attachment.h), steps the rods and refits the trees
// for the next substep. Bullet's own queries (rayTest, contactTest, contactPairTest,
// convexSweepTest) see the ropes' capsules; rope_queries.h maps a hit to the rope and its s.
//
// Ownership: the user owns the Bullet world, the bodies, the RopeWorld and the RopeObjects. The
// RopeWorld and the RopeObjects may be destroyed in either order (each unregisters itself).
// The RopeWorld must be destroyed before the Bullet world (it removes its action and the ropes'
// objects and restores the dispatcher's create functions), as every object a Bullet world holds must
// be removed from it before the world goes. If the world is destroyed first anyway, a RopeWorld that
// held a rope at that moment notices it through the rope's object (Bullet's world destructor clears
// its broadphase handle) and from then on leaves the dead world and its dispatcher alone, in its
// destructor too; a RopeWorld that held no rope then has nothing to notice it by, and destroying it
// after its world is undefined behaviour.
//
// Failures: nothing is thrown out of stepSimulation. A rope whose substep fails (a failed solve, an
// exception from rope code or the narrowphase) keeps its last good state; its RopeStepRecord says why
// and RopeObject::warnings() counts it, and the other ropes and the Bullet world go on. A body with a
// non-finite transform, velocity or mass is passed over for the substep and counted. A substep with
// a time step that is not finite and > 0 is skipped; an exception thrown by the substep callback is
// caught. Both are counted in warnings() (rope_warnings.h).
//
// Bodies that leave: a body a rope is attached to may be removed from the Bullet world (and deleted)
// between steps. Each substep the RopeWorld checks, by comparing pointers with the world's collision
// object array (never dereferencing them), that every attached body is still there, and drops the
// attachments of one that is not (RopeStepRecord::droppedAttachments, RopeWarnings::droppedAttachments).
// Contacts are found afresh each substep from Bullet's dispatch, whose pairs go with removed bodies.

#include <BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h>

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/contact_report.h"
#include "bullet_bridge/collision_object/rope_dispatch.h"
#include "bullet_bridge/friction_combination.h"
#include "bullet_bridge/rope_object.h"
#include "bullet_bridge/contact/body_contacts.h"
#include "bullet_bridge/contact/rope_rope_contact.h"
#include "bullet_bridge/rope_warnings.h"

namespace rope::bullet {

class FasterOfTwo;
class SideThread;

class RopeWorld {
  friend class RopeObject;         // reads the friction combiner
  friend class RopePairAlgorithm;  // lists the rope pairs Bullet's dispatch made
 public:
  // Throws InvalidArgument("world", ...) if the world's dispatcher is not a btCollisionDispatcher or
  // the world has a RopeWorld already (collision_object/rope_dispatch.h).
  explicit RopeWorld(btDiscreteDynamicsWorld& world);
  ~RopeWorld();
  RopeWorld(const RopeWorld&) = delete;
  RopeWorld& operator=(const RopeWorld&) = delete;

  // Registers the rope's object in the broadphase (settings().collisionGroup / collisionMask).
  // Throws InvalidArgument("rope", ...) if the rope is already in this or another world.
  void addRope(RopeObject& rope);
  // Takes the rope's object out again; its attachments stay defined but act only in a world.
  // Throws InvalidArgument("rope", ...) if the rope is not in this world.
  void removeRope(RopeObject& rope);
  bool contains(const RopeObject& rope) const;
  // True while the ropes' substep runs (inside Bullet's stepSimulation, the substep callback included).
  bool stepping() const { return stepping_; }
  const std::vector<RopeObject*>& ropes() const { return ropes_; }

  btDiscreteDynamicsWorld& dynamicsWorld() { return world_; }
  const btDiscreteDynamicsWorld& dynamicsWorld() const { return world_; }
  // True if the object is one of the Bullet world's collision objects (and not a rope's).
  bool containsBody(const btCollisionObject& object) const;

  // The contacts and rope states of the last substep; the callback (if set) sees every substep. An
  // exception the callback throws is caught and counted (warnings().callbackExceptions, lastError()).
  const ContactReport& lastReport() const { return report_; }
  void setSubstepCallback(std::function<void(const ContactReport&)> callback) { callback_ = std::move(callback); }

  // Warnings counted since the RopeWorld was created (rope_warnings.h); each rope counts its own in
  // RopeObject::warnings(). lastError(): the message of the last exception caught at world level.
  const RopeWorldWarnings& warnings() const { return warnings_; }
  const std::string& lastError() const { return lastError_; }

  // Friction of rope-body and rope-rope contacts (friction_combination.h). By default Bullet's rule,
  // the product of the two coefficients clamped to 10 (rope: BulletRopeSettings::friction; body:
  // btCollisionObject::getFriction()); a combiner set here replaces it for every rope of this world
  // from the next substep on (an empty function restores the default). It runs inside
  // stepSimulation and must return a finite value >= 0: anything else (or an exception) fails that
  // rope's substep, which is counted (RopeObject::warnings()) and leaves the rope as it was.
  void setBodyFrictionCombiner(BodyFrictionCombiner combiner) { bodyFrictionCombiner_ = std::move(combiner); }
  void setRopeFrictionCombiner(RopeFrictionCombiner combiner) { ropeRopeContacts_.setFrictionCombiner(std::move(combiner)); }

  // Where a substep's rope-rope and self-contact detection runs. The results are bit for bit the
  // same either way (the same work in another order); only the wall-clock time of a step with ropes
  // near each other or themselves changes.
  enum class ContactDetectionThread {
    kCaller,  // the thread that steps the world, in turn with the ropes' body contacts and trials
    // A second thread, owned by this RopeWorld, beside the ropes' body contacts and trials, in every
    // substep after one with at least 64 capsule pairs to test (fewer are not worth the hand-over).
    // The 2 m pile's step takes about two thirds of the time on an idle second core; a core busy with
    // another program can make it longer. It runs no user code and starts at the first such substep.
    kSide,
    // kSide or kCaller, whichever this RopeWorld timed faster lately: in such substeps it tries both
    // (8 substeps each, alternating) and then runs the faster for 240 substeps, and so on.
    kFaster,
  };
  // Default: kFaster if the machine has more than one hardware thread
  // (std::thread::hardware_concurrency()), else kCaller. Throws InvalidArgument("where", ...) for a
  // value that is none of the three, and changes nothing then.
  void setContactDetectionThread(ContactDetectionThread where);
  ContactDetectionThread contactDetectionThread() const { return detectionThread_; }

  // Whether btDiscreteDynamicsWorld::debugDrawWorld also draws the ropes (rope_debug_draw.h). Default on.
  void setDebugDrawEnabled(bool enabled) { debugDraw_ = enabled; }
  bool debugDrawEnabled() const { return debugDraw_; }

 private:
  class Action;
  void substep(double h);
  // The parts of substep(); each rope's own failures are caught around its calls.
  void startReport(double h);
  void skipSubstep(double h);
  void findCandidates(double h);
  // Adds to candidates_ the bodies that can cross more than Bullet's broadphase slack in the substep
  // (rope_world.cpp says why), each for the ropes its swept box meets.
  void addFastBodies(double h);
  // The ropes' part of a substep, rope by rope (stepRopesInTurn, then solveRopeContacts), or with the
  // contact detection on the side thread (stepRopesWithSideDetection; sideDetectionWorthTrying()
  // says when it may be).
  void stepRopesInTurn(double h);
  bool sideDetectionWorthTrying() const;
  void stepRopesWithSideDetection(double h);
  // Before a rope's begin: drops departed bodies' attachments, orders its candidates, sets gravity.
  void readyRope(std::size_t r);
  // After a rope's begin and self-contact walk: finishes it at once if it can (finishesAlone) and
  // sets its stage.
  void settleStage(std::size_t r, bool resting, bool selfPaired, double h);
  // findRopeContacts then respondToRopeContacts: RopeRopeContacts::detect on the pairs (their ropes
  // renumbered) and RopeRopeContacts::respond.
  void solveRopeContacts(double h);
  void findRopeContacts(double h);
  void respondToRopeContacts(double h);
  void runCallback();
  void failRopeContacts(const char* message);
  void recoverFromException(const char* message) noexcept;

  // Rope-rope capsule pairs of two ropes from their trees (ropeA < ropeB by world index).
  void collideTrees(const RopeObject& a, const RopeObject& b);
  // The rope's self-contact pairs (if its settings want them) for the substep h (s); true if it
  // found any.
  bool collideSelf(const RopeObject& rope, double h);
  // collideSelf's search: the rope's capsule pairs that the rope-rope solve may keep, appended to
  // capsulePairs_ (rope_world.cpp says how).
  void findSelfPairs(const RopeObject& rope, double h);

  btDiscreteDynamicsWorld& world_;
  std::unique_ptr<RopeDispatch> dispatch_;
  RopePairs ropePairs_;  // filled by Bullet's dispatch (collision_object/rope_dispatch.h)
  std::unique_ptr<Action> action_;
  std::vector<std::pair<const btDbvtNode*, const btDbvtNode*>> treeStack_;  // scratch of the tree-tree walks
  struct SelfWalk;                     // scratch of a long rope's self-contact walk (rope_world.cpp)
  std::unique_ptr<SelfWalk> selfWalk_;
  std::vector<std::pair<RopeObject*, RopeObject*>> ropeRopePairs_;  // scratch
  std::vector<RopeObject*> ropes_;
  std::vector<std::vector<const btCollisionObject*>> candidates_;  // per rope, scratch
  std::vector<btBroadphaseProxy*> fastBodyRopes_;                   // scratch of addFastBodies
  std::vector<std::pair<const btRigidBody*, int>> bodyAttachmentCounts_;  // per substep, sorted by body
  std::vector<RopeCapsulePair> capsulePairs_;  // scratch; world indices until solveRopeContacts renumbers them
  std::vector<RopeCapsulePair> sortedPairs_;                        // scratch of sortCapsulePairs
  std::vector<int> pairBuckets_, ropeOffsets_;                     // scratch of sortCapsulePairs
  // Where each rope (by world index) is in the substep: named by a capsule pair (it waits for the
  // rope-rope solve), begun and waiting for its end, finished already, or resting.
  enum class RopeStage : unsigned char { kPaired, kBegun, kFinished, kRested };
  std::vector<RopeStage> ropeStages_;
  // The step's storage lent to each rope for its visit (RopeObject::swapStepScratch): a rope finished
  // in its visit gives it back; one that waits keeps it, and the world keeps the rope's own.
  RopeObject::StepScratch stepScratch_;
  std::vector<RopeObject*> pairRopes_;  // the ropes the capsule pairs name, in world order
  std::vector<int> pairRopeIndex_;      // per rope: its index in pairRopes_, -1 if none
  struct PairRopeContacts {
    int active = 0, near = 0;
    double overlap = 0.0;  // m
  };
  std::vector<PairRopeContacts> pairRopeContacts_;  // per paired rope, scratch of solveRopeContacts
  // Puts capsulePairs_ (indices into pairRopes_) in (ropeA, capsuleA, ropeB, capsuleB) order in
  // O(pairs + capsules of the paired ropes).
  void sortCapsulePairs();
  RopeRopeContacts ropeRopeContacts_;
  std::string detectFailure_;  // findRopeContacts: the exception's message, empty if none
  double findSeconds_ = 0.0;   // findRopeContacts' time, s (part of ContactReport::ropeContactSeconds)
  // Side detection (stepRopesWithSideDetection): the thread, and what its job reads and writes.
  ContactDetectionThread detectionThread_ = ContactDetectionThread::kCaller;
  std::unique_ptr<SideThread> side_;
  std::unique_ptr<FasterOfTwo> fasterWay_;  // kFaster: way 1 is the side thread
  // A substep uses the side thread if the last one had at least this many capsule pairs to test: a
  // hand-over costs microseconds, the pile's detection about 600 (a few pairs are not worth it).
  static constexpr std::size_t kMinPairsBeside = 64;
  std::size_t lastPairCount_ = 0;  // capsule pairs of the last substep, before the solve's filter
  double sideStep_ = 0.0;          // h of the side job (findRopeContacts), s
  std::vector<unsigned char> restingAtStart_, prepared_, selfPaired_;  // per rope, that substep
  ContactReport report_;
  std::function<void(const ContactReport&)> callback_;
  BodyFrictionCombiner bodyFrictionCombiner_;
  RopeWorldWarnings warnings_;
  std::string lastError_;
  bool debugDraw_ = true;
  bool stepping_ = false;
  bool worldGone_ = false;  // a rope's object showed that the Bullet world was destroyed
};

}  // namespace rope::bullet
