// SPDX-License-Identifier: MIT
#include "bullet_bridge/rope_world.h"

#include <BulletCollision/BroadphaseCollision/btOverlappingPairCache.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>
#include <BulletDynamics/Dynamics/btActionInterface.h>
#include <LinearMath/btAabbUtil2.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <thread>
#include <tuple>

#include "bullet_bridge/detail/body_state.h"
#include "bullet_bridge/capsule_proxies.h"
#include "bullet_bridge/detail/guarded_call.h"
#include "bullet_bridge/detail/self_pair_cache.h"
#include "bullet_bridge/detail/faster_of_two.h"
#include "bullet_bridge/detail/side_thread.h"
#include "bullet_bridge/detail/tree_pairs.h"
#include "bullet_bridge/kinematic_rope.h"
#include "bullet_bridge/rope_debug_draw.h"
#include "rope/common/error.h"
#include "rope/common/prefetch.h"

namespace rope::bullet {

namespace {

// Up to this many capsules a rope's self-contact candidates are found by testing every pair of its
// leaf boxes (at most 105 pairs of 16) rather than by walking a tree (RopeWorld::findSelfPairs).
constexpr int kLinearSelfScanCapsules = 16;
// How far (rope radii) a long rope's self-contact walk grows the boxes whose pairs it keeps between
// substeps (self_pair_cache.h). The 2 m pile's step was shortest at 0.1 of 0.05, 0.1, 0.2, 0.5 and 1:
// more slack keeps more pairs to test each substep, less walks again more often; the knot scene's
// step did not change with it.
constexpr double kSelfPairSlack = 0.1;

}  // namespace

// Bullet calls updateAction once per internal substep with dt = the fixed step, after collision
// detection, the solver and integration of that substep (btDiscreteDynamicsWorld::
// internalSingleStepSimulation -> updateActions).
class RopeWorld::Action : public btActionInterface {
 public:
  explicit Action(RopeWorld& owner) : owner_(owner) {}
  // Nothing may leave Bullet's step: each rope's failures are caught around its own calls in
  // substep(); this catches what is left (an allocation failure, say), drops every rope's pending
  // trial so that each keeps its last committed state, and counts it.
  void updateAction(btCollisionWorld*, btScalar dt) override {
    struct Stepping {
      explicit Stepping(bool& flag) : flag(flag) { flag = true; }
      ~Stepping() { flag = false; }
      bool& flag;
    } stepping(owner_.stepping_);
    guardedCall([&] { owner_.substep(static_cast<double>(dt)); },
                [&](const char* message) { owner_.recoverFromException(message); });
  }
  void debugDraw(btIDebugDraw* drawer) override {
    if (owner_.debugDraw_ && drawer != nullptr) drawRopes(owner_, *drawer);
  }

 private:
  RopeWorld& owner_;
};

double ContactReport::maxPenetration() const {
  double deepest = 0.0;
  for (const RopeStepRecord& rope : ropes) deepest = std::max(deepest, rope.maxPenetration);
  return deepest;
}

double ContactReport::maxSelfOverlap() const {
  double deepest = 0.0;
  for (const RopePairContactRecord& contact : ropeContacts) deepest = std::max(deepest, contact.depth);
  return deepest;
}

struct RopeWorld::SelfWalk {
  std::vector<btDbvtVolume> boxes;  // per capsule: its axis's box, grown (findSelfPairs)
  std::vector<double> key;          // what the walk's filter depends on: rest arclengths, exclusion
  std::vector<SelfPairCache> kept;  // per rope, by world index (a stale entry only misses)
  IndexedBoxTree tree;
  std::vector<IndexedNodePair> stack;
};

RopeWorld::RopeWorld(btDiscreteDynamicsWorld& world)
    : world_(world),
      dispatch_(std::make_unique<RopeDispatch>(world)),
      action_(std::make_unique<Action>(*this)),
      selfWalk_(std::make_unique<SelfWalk>()),
      detectionThread_(std::thread::hardware_concurrency() > 1 ? ContactDetectionThread::kFaster
                                                               : ContactDetectionThread::kCaller),
      side_(std::make_unique<SideThread>()),
      fasterWay_(std::make_unique<FasterOfTwo>()) {
  world_.addAction(action_.get());
}

RopeWorld::~RopeWorld() {
  while (!ropes_.empty()) removeRope(*ropes_.back());
  if (worldGone_) {
    dispatch_->detach();
  } else {
    world_.removeAction(action_.get());
  }
}

bool RopeWorld::contains(const RopeObject& rope) const {
  return std::find(ropes_.begin(), ropes_.end(), &rope) != ropes_.end();
}

bool RopeWorld::containsBody(const btCollisionObject& object) const {
  if (CapsuleProxies::ropeOf(object) != nullptr) return false;
  const int index = object.getWorldArrayIndex();
  const btCollisionObjectArray& objects = world_.getCollisionObjectArray();
  return index >= 0 && index < objects.size() && objects[index] == &object;
}

void RopeWorld::addRope(RopeObject& rope) {
  if (contains(rope)) throw InvalidArgument("rope", "already in this world", "must not be added twice");
  if (rope.world() != nullptr) throw InvalidArgument("rope", "in another world", "must be removed from it first");
  rope.worldIndex_ = static_cast<int>(ropes_.size());
  ropes_.push_back(&rope);
  rope.enterWorld(*this, world_);
  // Filled anew each substep before any rope reads it; the rope keeps the pointer until it leaves.
  rope.shareBodyAttachmentCounts(&bodyAttachmentCounts_);
}

void RopeWorld::removeRope(RopeObject& rope) {
  const auto it = std::find(ropes_.begin(), ropes_.end(), &rope);
  if (it == ropes_.end()) throw InvalidArgument("rope", "not in this world", "must have been added to it");
  // Bullet's world destructor clears the broadphase handles of the objects still in it: if it ran
  // already, the world is gone and must not be touched again (rope_world.h, "Ownership").
  if (rope.proxies().orphaned()) worldGone_ = true;
  rope.leaveWorld();
  rope.worldIndex_ = -1;
  ropeRopeContacts_.forget(rope);  // its distributed contacts' stick state names it by address
  ropes_.erase(it);
  for (std::size_t i = 0; i < ropes_.size(); ++i) ropes_[i]->worldIndex_ = static_cast<int>(i);
  // The last report must not point at a rope that may be destroyed next.
  report_.contacts.clear();
  report_.ropes.clear();
  report_.ropeContacts.clear();
  report_.attachments.clear();
}

void RopeWorld::sortCapsulePairs() {
  // Least-significant-digit radix sort with two stable counting passes over global capsule numbers
  // (the paired ropes' capsules numbered in rope order): by the second capsule, then by the first.
  // O(pairs + capsules of the paired ropes); the comparison sort of every pair was 8 % of the knot
  // scene's step, and insertion sort within the first capsule's bucket 11 % (a capsule of a tight knot
  // pairs with dozens). A rope's range covers its capsule count and every capsule index a pair names
  // (a pair found before a rebuild may name one past the end; the solve skips it), so the order is
  // (ropeA, capsuleA, ropeB, capsuleB) whatever the indices.
  ropeOffsets_.assign(pairRopes_.size() + 1, 0);
  for (std::size_t k = 0; k < pairRopes_.size(); ++k) {
    ropeOffsets_[k + 1] = pairRopes_[k]->proxies().size();
  }
  for (const RopeCapsulePair& p : capsulePairs_) {
    int& a = ropeOffsets_[static_cast<std::size_t>(p.ropeA) + 1];
    int& b = ropeOffsets_[static_cast<std::size_t>(p.ropeB) + 1];
    a = std::max(a, p.capsuleA + 1);
    b = std::max(b, p.capsuleB + 1);
  }
  for (std::size_t k = 0; k < pairRopes_.size(); ++k) ropeOffsets_[k + 1] += ropeOffsets_[k];
  const int capsules = ropeOffsets_.back();
  const auto first = [&](const RopeCapsulePair& p) {
    return static_cast<std::size_t>(ropeOffsets_[static_cast<std::size_t>(p.ropeA)] + p.capsuleA);
  };
  const auto second = [&](const RopeCapsulePair& p) {
    return static_cast<std::size_t>(ropeOffsets_[static_cast<std::size_t>(p.ropeB)] + p.capsuleB);
  };
  sortedPairs_.resize(capsulePairs_.size());
  const auto countingPass = [&](const std::vector<RopeCapsulePair>& from, std::vector<RopeCapsulePair>& to,
                                const auto& key) {
    pairBuckets_.assign(static_cast<std::size_t>(capsules) + 1, 0);
    for (const RopeCapsulePair& p : from) ++pairBuckets_[key(p) + 1];
    for (int c = 0; c < capsules; ++c) pairBuckets_[static_cast<std::size_t>(c) + 1] += pairBuckets_[static_cast<std::size_t>(c)];
    for (const RopeCapsulePair& p : from) to[static_cast<std::size_t>(pairBuckets_[key(p)]++)] = p;
  };
  countingPass(capsulePairs_, sortedPairs_, second);
  countingPass(sortedPairs_, capsulePairs_, first);
}

void RopeWorld::substep(double h) {
  if (!(std::isfinite(h) && h > 0.0)) {
    skipSubstep(h);
    return;
  }
  findCandidates(h);
  startReport(h);
  // Body attachments per body over all ropes (seriesWithBody shares the body among them).
  bodyAttachmentCounts_.clear();
  for (const RopeObject* rope : ropes_) {
    for (const Attachment& attachment : rope->attachments()) {
      if (attachment.body != nullptr) bodyAttachmentCounts_.emplace_back(attachment.body, 1);
    }
  }
  std::sort(bodyAttachmentCounts_.begin(), bodyAttachmentCounts_.end());
  std::size_t unique = 0;
  for (std::size_t i = 0; i < bodyAttachmentCounts_.size(); ++i) {
    if (unique > 0 && bodyAttachmentCounts_[unique - 1].first == bodyAttachmentCounts_[i].first) {
      ++bodyAttachmentCounts_[unique - 1].second;
    } else {
      bodyAttachmentCounts_[unique++] = bodyAttachmentCounts_[i];
    }
  }
  bodyAttachmentCounts_.resize(unique);
  ropeStages_.assign(ropes_.size(), RopeStage::kRested);
  for (const RopeCapsulePair& pair : capsulePairs_) {
    ropeStages_[static_cast<std::size_t>(pair.ropeA)] = RopeStage::kPaired;
    ropeStages_[static_cast<std::size_t>(pair.ropeB)] = RopeStage::kPaired;
  }
  const bool timed = detectionThread_ == ContactDetectionThread::kFaster && sideDetectionWorthTrying();
  const auto start = std::chrono::steady_clock::now();
  if (detectionThread_ == ContactDetectionThread::kSide ? sideDetectionWorthTrying() : timed && fasterWay_->next() == 1) {
    stepRopesWithSideDetection(h);
  } else {
    stepRopesInTurn(h);
    solveRopeContacts(h);
  }
  if (timed) fasterWay_->record(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());

  for (std::size_t r = 0; r < ropes_.size(); ++r) {
    RopeObject* rope = ropes_[r];
    // By now the first ropes' data has left the caches again: the same staged hints as above, for
    // what this pass reads of a finished rope, and everything for one that still has to finish.
    if (r + 3 < ropes_.size()) ropes_[r + 3]->prefetchObject();
    if (r + 2 < ropes_.size()) ropes_[r + 2]->prefetchParts();
    if (r + 1 < ropes_.size()) {
      if (ropeStages_[r + 1] == RopeStage::kFinished) {
        ropes_[r + 1]->prefetchRecords();
      } else {
        ropes_[r + 1]->prefetchTrial();
      }
    }
    if (!rope->resting() && ropeStages_[r] != RopeStage::kFinished) {
      guardedCall([&] { rope->finishSubstep(h); }, [&](const char* message) { rope->failSubstep(message); });
    }
    if (!rope->resting()) rope->announceBox();  // a resting rope's box went to Bullet in restSubstep
    rope->countSubstep();
    report_.contacts.insert(report_.contacts.end(), rope->contacts().begin(), rope->contacts().end());
    report_.ropes.push_back(rope->lastStep());
    report_.attachments.insert(report_.attachments.end(), rope->attachmentLoads().begin(),
                               rope->attachmentLoads().end());
  }
  runCallback();
}

void RopeWorld::readyRope(std::size_t r) {
  RopeObject& rope = *ropes_[r];
  // Bodies removed from the world (perhaps deleted) since the last substep lose their attachments
  // before anything reads them.
  rope.dropDepartedAttachments(world_);
  std::vector<const btCollisionObject*>& list = candidates_[r];
  // Deterministic order (pointer values are not): by the body's index in the world.
  std::sort(list.begin(), list.end(), [](const btCollisionObject* a, const btCollisionObject* b) {
    return a->getWorldArrayIndex() < b->getWorldArrayIndex();
  });
  list.erase(std::unique(list.begin(), list.end()), list.end());
  if (rope.settings().gravitySource == BulletRopeSettings::GravitySource::kWorld) {
    const btVector3 g = world_.getGravity() * static_cast<btScalar>(rope.settings().gravityScale);
    const Vec3 gravity(static_cast<double>(g.x()), static_cast<double>(g.y()), static_cast<double>(g.z()));
    // A non-finite world gravity leaves the rope's as it was (no arithmetic on it: FP traps).
    if (std::isfinite(gravity.x()) && std::isfinite(gravity.y()) && std::isfinite(gravity.z())) {
      rope.rod().setGravity(gravity);
    }
  }
}

void RopeWorld::settleStage(std::size_t r, bool resting, bool selfPaired, double h) {
  RopeObject& rope = *ropes_[r];
  if (selfPaired) ropeStages_[r] = RopeStage::kPaired;
  const bool paired = ropeStages_[r] == RopeStage::kPaired;
  if (resting) {
    if (!paired) ropeStages_[r] = RopeStage::kRested;
  } else {
    if (!paired && rope.finishesAlone()) {
      guardedCall([&] { rope.finishSubstep(h); }, [&](const char* message) { rope.failSubstep(message); });
      ropeStages_[r] = RopeStage::kFinished;
      if (!rope.rod().hasTrial()) rope.swapStepScratch(stepScratch_);
    } else if (!paired) {
      ropeStages_[r] = RopeStage::kBegun;
    }
  }
  // No pair names the rope: no rope-rope contact record can (solveRopeContacts records the others).
  if (!paired) rope.recordRopeContacts(0, 0.0, false);
}

void RopeWorld::stepRopesInTurn(double h) {
  // Each rope is taken through as much of its substep as it can in one visit, while its data is in
  // the cache: a separate pass over all ropes per phase (self-contact trees, begin, rope-contact
  // bookkeeping, end) fetched every rope's data from memory again each time once the ropes outgrew
  // the caches (1000 ropes resting on a box cost 1.56 times as much per rope as 100). A rope that no
  // rope-rope or self-contact pair names and whose end of substep pushes no dynamic body
  // (RopeObject::finishesAlone) is finished at once: nothing it does then can reach another rope
  // before that rope's own end of substep (the coupled rope-rope solve takes only the ropes its pairs
  // name), so the results are the same as finishing it after every rope has begun. The new boxes
  // reach Bullet's broadphase in world order after all ropes are done, as before.
  for (std::size_t r = 0; r < ropes_.size(); ++r) {
    RopeObject& rope = *ropes_[r];
    // The ropes' states outgrow the caches (1000 ropes: ~20 MB touched per substep), so each rope's
    // first reads waited for memory: ask for the next ropes' data in stages (RopeObject::
    // prefetchObject) while this one is stepped (rope/common/prefetch.h).
    if (r + 3 < ropes_.size()) ropes_[r + 3]->prefetchObject();
    if (r + 2 < ropes_.size()) ropes_[r + 2]->prefetchParts();
    if (r + 1 < ropes_.size()) {
      ropes_[r + 1]->prefetchState();
      prefetchVector(candidates_[r + 1]);
    }
    readyRope(r);
    const std::vector<const btCollisionObject*>& list = candidates_[r];
    const bool resting = rope.resting();
    if (resting) {
      guardedCall([&] { rope.restSubstep(list, h); }, [&](const char* message) { rope.failSubstep(message); });
    } else {
      // A trial left pending by a failure keeps the rope's own storage (RopeObject::swapStepScratch).
      if (!rope.rod().hasTrial()) rope.swapStepScratch(stepScratch_);
      guardedCall([&] { rope.beginSubstep(list, h); }, [&](const char* message) { rope.failSubstep(message); });
    }
    // Self-contact candidates: capsule pairs whose tree leaves (swept boxes) overlap. The tree is the
    // one the rope-rope pairs were found in (it is refitted only at the end of the substep; a winch
    // that changed the capsule count in the rope's begin added or dropped leaves), and the pairs are
    // sorted before the solve, so finding them here changes nothing but where the time goes. After
    // the rope's begin (winches, rebuild): the walk skips what the solve's filter would drop by the
    // capsules' rest arclengths (collideTrees), and those are the ones the solve reads. Guarded as the
    // begin is: those arclengths are evaluated on the rod, and nothing may throw out of a step.
    bool selfPaired = false;
    guardedCall([&] { selfPaired = collideSelf(rope, h); }, [&](const char* message) { rope.failSubstep(message); });
    settleStage(r, resting, selfPaired, h);
  }
}

bool RopeWorld::sideDetectionWorthTrying() const {
  // Worth a hand-over (a few microseconds each way) only where there are pairs to test: the last
  // substep's count predicts this one's (a rope that lies alone has none). Either way the results
  // are the same, bit for bit.
  return lastPairCount_ >= kMinPairsBeside;
}

void RopeWorld::setContactDetectionThread(ContactDetectionThread where) {
  if (where != ContactDetectionThread::kCaller && where != ContactDetectionThread::kSide &&
      where != ContactDetectionThread::kFaster) {
    throw InvalidArgument("where", std::to_string(static_cast<int>(where)),
                          "must be ContactDetectionThread::kCaller, kSide or kFaster");
  }
  detectionThread_ = where;
}

void RopeWorld::stepRopesWithSideDetection(double h) {
  // The rope-rope and self-contact detection (RopeRopeContacts::detect, after the self-contact walks)
  // reads only the ropes' capsules and their state before the step, which are settled once every
  // rope has run RopeObject::prepareSubstep; the body contacts and trial steps
  // (RopeObject::solveSubstepTrial) change neither. So the detection runs on the side thread while
  // this one solves the ropes' body contacts and trials: the same work as stepRopesInTurn in another
  // order, with the same results bit for bit (the ropes that finish alone are finished after every
  // rope has begun, which stepRopesInTurn says changes nothing). The self-contact walks stay here,
  // before the hand-over: on the side thread they made no measurable difference (the knot, 10
  // alternating runs, 0.92-1.04x), and here a walk's failure is this thread's to report.
  side_->wake();  // while the ropes are prepared
  const std::size_t count = ropes_.size();
  restingAtStart_.assign(count, 0);
  prepared_.assign(count, 0);
  selfPaired_.assign(count, 0);
  for (std::size_t r = 0; r < count; ++r) {
    RopeObject& rope = *ropes_[r];
    readyRope(r);
    restingAtStart_[r] = rope.resting() ? 1 : 0;
    if (rope.resting()) {
      guardedCall([&] { rope.restSubstep(candidates_[r], h); }, [&](const char* message) { rope.failSubstep(message); });
    } else {
      if (!rope.rod().hasTrial()) rope.swapStepScratch(stepScratch_);
      guardedCall([&] {
        rope.prepareSubstep(h);
        // The capsules' end speeds and rest arclengths are computed when first asked for and kept
        // (CapsuleProxies): asked here, the side thread and this one only read them.
        rope.proxies().endSpeeds(rope.rod());
        rope.proxies().endArcs(rope.rod());
        prepared_[r] = 1;
      }, [&](const char* message) { rope.failSubstep(message); });
    }
    // A rope whose walk fails fails its substep, here before its trial (stepRopesInTurn: after it,
    // which the failure then drops): either way it keeps its state.
    guardedCall([&] { selfPaired_[r] = collideSelf(rope, h) ? 1 : 0; },
                [&](const char* message) {
                  prepared_[r] = 0;
                  rope.failSubstep(message);
                });
    if (selfPaired_[r]) ropeStages_[r] = RopeStage::kPaired;  // as settleStage will
  }
  // From here until the side job ends, this thread reads and writes only the prepared ropes' trials,
  // loads, body contacts and records, and the job only the paired ropes' capsules and state before
  // the step, capsulePairs_ and the rope-rope solver; the report waits for it.
  struct WaitForSide {  // whatever is thrown below, the side job ends before this function does
    SideThread& side;
    ~WaitForSide() {
      try {
        side.wait();
      } catch (...) {  // the exception already on its way out is the one reported
      }
    }
  } waitForSide{*side_};
  sideStep_ = h;
  report_.detectedOnSideThread = true;
  side_->start([](void* world) {
    RopeWorld& self = *static_cast<RopeWorld*>(world);
    self.findRopeContacts(self.sideStep_);
  }, this);
  for (std::size_t r = 0; r < count; ++r) {
    if (!prepared_[r]) continue;
    RopeObject& rope = *ropes_[r];
    guardedCall([&] { rope.solveSubstepTrial(candidates_[r], h); }, [&](const char* message) { rope.failSubstep(message); });
  }
  side_->wait();  // rethrows what findRopeContacts let out (not the detection's own failures)
  for (std::size_t r = 0; r < count; ++r) settleStage(r, restingAtStart_[r] != 0, selfPaired_[r] != 0, h);
  respondToRopeContacts(h);
}

void RopeWorld::startReport(double h) {
  report_.substep += 1;
  report_.timeStep = h;
  report_.failure = "";
  report_.contacts.clear();
  report_.ropes.clear();
  report_.ropeContacts.clear();
  report_.attachments.clear();
  report_.ropeContactFailure = "";
  report_.detectedOnSideThread = false;
}

void RopeWorld::skipSubstep(double h) {
  ++warnings_.skippedSubsteps;
  startReport(h);
  report_.failure = "the substep's time step is not finite and > 0: no rope stepped";
  for (RopeObject* rope : ropes_) {
    rope->skipSubstep(report_.failure);
    rope->countSubstep();
    report_.ropes.push_back(rope->lastStep());
  }
  runCallback();
}

void RopeWorld::findCandidates(double h) {
  // The ropes' pairs Bullet's dispatch made (rope_dispatch.h): a rope and a body, or two ropes. Bullet
  // drops pairs whose boxes parted lazily, so the overlap is checked again.
  const auto scanStart = std::chrono::steady_clock::now();
  candidates_.resize(ropes_.size());
  for (auto& list : candidates_) list.clear();
  capsulePairs_.clear();
  ropeRopePairs_.clear();
  const auto inThisWorld = [this](const RopeObject* rope) { return rope->world_ == this && rope->worldIndex_ >= 0; };
  ropePairs_.forEach([&](const btCollisionObject* object0, const btCollisionObject* object1) {
    const btBroadphaseProxy* proxy0 = object0->getBroadphaseHandle();
    const btBroadphaseProxy* proxy1 = object1->getBroadphaseHandle();
    if (proxy0 == nullptr || proxy1 == nullptr) return;
    if (!TestAabbAgainstAabb2(proxy0->m_aabbMin, proxy0->m_aabbMax, proxy1->m_aabbMin, proxy1->m_aabbMax)) return;
    RopeObject* rope0 = CapsuleProxies::ropeOf(*object0);
    RopeObject* rope1 = CapsuleProxies::ropeOf(*object1);
    if (rope0 != nullptr && rope1 != nullptr) {
      if (inThisWorld(rope0) && inThisWorld(rope1)) ropeRopePairs_.emplace_back(rope0, rope1);
      return;
    }
    RopeObject* rope = rope0 != nullptr ? rope0 : rope1;
    const btCollisionObject* body = rope0 != nullptr ? object1 : object0;
    // Triggers and other objects that want no contact response get none from ropes either; a
    // kinematic rope's capsules want none from Bullet's solver but push dynamic ropes (kinematic_rope.h).
    if (rope == nullptr || !inThisWorld(rope)) return;
    if (!body->hasContactResponse() && KinematicRope::ropeOf(*body) == nullptr) return;
    candidates_[static_cast<std::size_t>(rope->worldIndex_)].push_back(body);
  });
  addFastBodies(h);
  // Rope-rope contact candidates (rope_rope_contact.h): capsule pairs whose tree leaves (swept boxes)
  // overlap. Self-contact candidates are found rope by rope in substep() (collideSelf).
  for (const auto& pair : ropeRopePairs_) collideTrees(*pair.first, *pair.second);
  report_.pairScanSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - scanStart).count();
}

bool RopeWorld::collideSelf(const RopeObject& rope, double h) {
  // Self-contact needs the rope's own group in its mask, as for a pair of two ropes.
  const BulletRopeSettings& settings = rope.settings();
  if (!settings.selfContact || (settings.collisionGroup & settings.collisionMask) == 0) return false;
  const auto start = std::chrono::steady_clock::now();
  const std::size_t before = capsulePairs_.size();
  findSelfPairs(rope, h);
  report_.pairScanSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return capsulePairs_.size() > before;
}

void RopeWorld::collideTrees(const RopeObject& a, const RopeObject& b) {
  const bool swap = b.worldIndex_ < a.worldIndex_;
  const RopeObject& first = swap ? b : a;
  const RopeObject& second = swap ? a : b;
  const int rope0 = first.worldIndex_, rope1 = second.worldIndex_;
  // The pairs' order is the walk's; sortCapsulePairs orders them before anything depends on it.
  overlappingLeafPairs(first.proxies().tree().m_root, second.proxies().tree().m_root, treeStack_,
                       [&](const btDbvtNode* leaf0, const btDbvtNode* leaf1) {
                         capsulePairs_.push_back(RopeCapsulePair{rope0, leaf0->dataAsInt, rope1, leaf1->dataAsInt});
                       });
}

void RopeWorld::findSelfPairs(const RopeObject& rope, double h) {
  // The solve drops every pair of capsules whose point pairs are all within the self-contact
  // exclusion along the rest curve (RopeRopeContacts::mayTouch), two thirds of a tight knot's leaf
  // pairs. The walk skips each pair of subtrees whose capsules are all that close: their capsule
  // ranges span less than the exclusion between the first's start and the last's end, in the rest
  // arclengths the solve reads (endArcs), so the solve sees the same pairs it keeps. The pairs' order
  // is the walk's; sortCapsulePairs orders them before anything depends on it.
  const int index = rope.worldIndex_;
  const CapsuleProxies& proxies = rope.proxies();
  const std::vector<double>& arcs = proxies.endArcs(rope.rod());
  const int lastCapsule = proxies.size() - 1;
  const double radius = rope.rod().settings().radius;
  const double exclusion = rope.settings().effectiveSelfContactExclusion(radius);
  const auto mayPairRanges = [&](int x0, int x1, int y0, int y1) {
    x1 = std::min(x1, lastCapsule);
    y1 = std::min(y1, lastCapsule);
    if (x0 > x1 || y0 > y1) return false;
    const double farthest = std::max(arcs[static_cast<std::size_t>(y1) + 1] - arcs[static_cast<std::size_t>(x0)],
                                     arcs[static_cast<std::size_t>(x1) + 1] - arcs[static_cast<std::size_t>(y0)]);
    return !(farthest < exclusion);
  };
  const auto add = [&](int capsule0, int capsule1) {
    // Neighbouring capsules of one rope always overlap and are never a contact.
    if (capsule1 - capsule0 > 1) capsulePairs_.push_back(RopeCapsulePair{index, capsule0, index, capsule1});
  };
  const int capsules = proxies.size();
  if (capsules <= kLinearSelfScanCapsules) {
    // A short rope: every pair of its leaf boxes in one array, not the walk over the tree's nodes,
    // which Bullet allocates one by one (a thousand ropes: a cache miss per node every substep). The
    // same pairs as the walk's (overlappingBoxPairs; sortCapsulePairs orders them): mayPair of two
    // capsule ranges holds whenever it holds for two capsules within them.
    overlappingBoxPairs(proxies.leafBoxes(), add,
                        [&](int capsule0, int capsule1) { return mayPairRanges(capsule0, capsule0, capsule1, capsule1); });
    return;
  }
  // A longer one: the walk over a tree of boxes by capsule index (IndexedBoxTree), not over its
  // btDbvt, whose subtrees hold capsules from all along the rope (Bullet shapes it by insertion
  // order), so that the exclusion drops whole subtrees of neighbours at once; and arrays, not nodes
  // allocated one by one (the btDbvt walk was 11 % of the 2 m pile's step, perf). Its boxes are not
  // the leaves (padded for rope-body contact and kept fat between refits) but each capsule axis's box
  // grown by half of what the solve's filter allows a pair (RopeRopeContacts::mayTouch: the radii, the
  // reach and the step's travel at both capsules' speeds), with a relative slack for rounding. Every
  // pair that filter keeps has meeting boxes here and meeting leaves in the tree, so the solve sees
  // exactly the pairs it saw from the tree, and fewer are found only to be dropped (the 2 m pile: 5,100
  // pairs per substep instead of 6,400, for the 3,550 the filter keeps).
  const std::vector<double>& speeds = proxies.endSpeeds(rope.rod());
  const double margin = RopeRopeContacts::pairMargin(rope.settings().speculativeMargin, radius,
                                                     rope.settings().speculativeMargin, radius);
  std::vector<btDbvtVolume>& boxes = selfWalk_->boxes;
  boxes.resize(static_cast<std::size_t>(capsules));
  for (int i = 0; i < capsules; ++i) {
    const Capsule capsule = proxies.capsule(i);
    const double speed = std::max(speeds[static_cast<std::size_t>(i)], speeds[static_cast<std::size_t>(i) + 1]);
    btVector3 low = capsule.a, high = capsule.a;
    low.setMin(capsule.b);
    high.setMax(capsule.b);
    // The slack: 1e-6 of the reach and of the coordinates (m), far above the rounding of either in
    // float or double, far below anything the filter distinguishes.
    btVector3 far = low.absolute();
    far.setMax(high.absolute());
    const double size = std::max({1.0, static_cast<double>(far.x()), static_cast<double>(far.y()), static_cast<double>(far.z())});
    const btScalar grow = static_cast<btScalar>((radius + 0.5 * margin + h * speed) * (1.0 + 1e-6) + 1e-6 * size);
    boxes[static_cast<std::size_t>(i)] = btDbvtVolume::FromMM(low - btVector3(grow, grow, grow), high + btVector3(grow, grow, grow));
  }
  // The pairs are kept between substeps while the boxes stay within their kept ones grown by
  // kSelfPairSlack radii (self_pair_cache.h): exactly the walk's pairs, without the walk while the
  // rope lies still.
  std::vector<double>& key = selfWalk_->key;
  key.assign(arcs.begin(), arcs.end());
  key.push_back(exclusion);
  if (selfWalk_->kept.size() < ropes_.size()) selfWalk_->kept.resize(ropes_.size());
  selfWalk_->kept[static_cast<std::size_t>(index)].find(boxes, key, static_cast<btScalar>(kSelfPairSlack * radius),
                                                       selfWalk_->tree, selfWalk_->stack, add, mayPairRanges);
}

void RopeWorld::addFastBodies(double h) {
  // The ropes act after Bullet has integrated the bodies (updateActions), on pairs whose boxes Bullet
  // made before that integration: a body's box spans its motion over the substep just integrated
  // (btCollisionWorld::updateSingleAabb: from where it was to where it was predicted to be) plus
  // gContactBreakingThreshold, and not the motion it will make before the ropes look again. A body
  // that moves further than that slack per substep (a 50 m/s box at 1/240 s: 0.21 m against 0.02 m)
  // can be on the far side of a rope by the time the rope first sees it, and the penalty contact
  // then throws the rope (reliability_extremes_test). Such bodies are paired here with every rope
  // their box, grown by what they can cover in the substep (sweptReach), meets in the broadphase, so
  // that the speculative contact catches them before they penetrate. One pass over the world's
  // objects per substep; a slow body is never added, which leaves slow scenes as they were.
  const btScalar slack = gContactBreakingThreshold;
  btBroadphaseInterface* broadphase = world_.getBroadphase();
  btOverlappingPairCache* pairCache = broadphase->getOverlappingPairCache();
  btDispatcher* dispatcher = world_.getDispatcher();
  struct RopesMet : btBroadphaseAabbCallback {
    std::vector<btBroadphaseProxy*>* found = nullptr;
    bool process(const btBroadphaseProxy* proxy) override {
      const auto* object = static_cast<const btCollisionObject*>(proxy->m_clientObject);
      if (object != nullptr && CapsuleProxies::ropeOf(*object) != nullptr) {
        found->push_back(const_cast<btBroadphaseProxy*>(proxy));
      }
      return true;
    }
  } ropesMet;
  ropesMet.found = &fastBodyRopes_;
  const btCollisionObjectArray& objects = world_.getCollisionObjectArray();
  for (int i = 0; i < objects.size(); ++i) {
    btCollisionObject* body = objects[i];
    if (btRigidBody::upcast(body) == nullptr || !body->hasContactResponse()) continue;
    btBroadphaseProxy* proxy = body->getBroadphaseHandle();
    if (proxy == nullptr) continue;
    const double reach = sweptReach(*body, h);
    // A NaN body is the rope's to skip and count (BodyContacts::gather); isfinite first, since an
    // ordered comparison with NaN raises FE_INVALID.
    if (!std::isfinite(reach) || !(reach > static_cast<double>(slack))) continue;  // slow
    const btScalar grow = static_cast<btScalar>(reach);
    fastBodyRopes_.clear();
    broadphase->aabbTest(proxy->m_aabbMin - btVector3(grow, grow, grow), proxy->m_aabbMax + btVector3(grow, grow, grow),
                         ropesMet);
    for (btBroadphaseProxy* ropeProxy : fastBodyRopes_) {
      // Bullet's own filters, as for a pair it made: collision groups and masks (or the user's filter
      // callback), then the dispatcher's test (ignored pairs, two sleeping objects).
      if (pairCache != nullptr && !pairCache->needsBroadphaseCollision(proxy, ropeProxy)) continue;
      const auto* ropeObject = static_cast<const btCollisionObject*>(ropeProxy->m_clientObject);
      if (dispatcher != nullptr && !dispatcher->needsCollision(body, ropeObject)) continue;
      RopeObject* rope = CapsuleProxies::ropeOf(*ropeObject);
      if (rope->world_ != this || rope->worldIndex_ < 0) continue;
      candidates_[static_cast<std::size_t>(rope->worldIndex_)].push_back(body);
    }
  }
}

void RopeWorld::solveRopeContacts(double h) {
  findRopeContacts(h);
  respondToRopeContacts(h);
}

void RopeWorld::findRopeContacts(double h) {
  // Rope-rope and self-contact, coupled into the trials of the ropes the pairs name (in world order,
  // renumbered: a rope no pair names has no contact to find, and its trial may be committed already);
  // pairs in a fixed order (the pair cache's order depends on pointer hashes).
  const auto start = std::chrono::steady_clock::now();
  detectFailure_.clear();
  lastPairCount_ = capsulePairs_.size();
  findSeconds_ = 0.0;
  if (capsulePairs_.empty()) return;
  pairRopes_.clear();
  pairRopeIndex_.assign(ropes_.size(), -1);
  for (std::size_t r = 0; r < ropes_.size(); ++r) {
    if (ropeStages_[r] != RopeStage::kPaired) continue;
    pairRopeIndex_[r] = static_cast<int>(pairRopes_.size());
    pairRopes_.push_back(ropes_[r]);
  }
  for (RopeCapsulePair& pair : capsulePairs_) {
    pair.ropeA = pairRopeIndex_[static_cast<std::size_t>(pair.ropeA)];
    pair.ropeB = pairRopeIndex_[static_cast<std::size_t>(pair.ropeB)];
  }
  guardedCall(
      [&] {
        // Distant pairs out first: the tree's leaves are padded for rope-body contact, so in a knot
        // most of its pairs are neighbours or far apart (rope_rope_contact.h).
        ropeRopeContacts_.prepare(pairRopes_, h);
        ropeRopeContacts_.dropDistantPairs(capsulePairs_);
        sortCapsulePairs();
        ropeRopeContacts_.detect(pairRopes_, capsulePairs_);
      },
      [&](const char* message) { detectFailure_ = message; });
  findSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void RopeWorld::respondToRopeContacts(double h) {
  const auto ropeStart = std::chrono::steady_clock::now();
  if (capsulePairs_.empty()) {
    ropeRopeContacts_.forgetAll();  // no rope near another: nothing sticks
    report_.ropeContactSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - ropeStart).count();
    return;
  }
  if (!detectFailure_.empty()) {
    failRopeContacts(detectFailure_.c_str());
  } else {
    guardedCall(
        [&] {
          const int ropeContacts = ropeRopeContacts_.respond(pairRopes_, h, report_.ropeContacts);
          if (ropeContacts < 0) {
            report_.ropeContactFailure = "the coupled rope-rope contact solve failed; contacts skipped";
            ++warnings_.ropeContactFailures;
            ropeRopeContacts_.forgetAll();
          }
        },
        [&](const char* message) { failRopeContacts(message); });
  }
  // Each paired rope's records, in one pass over the records.
  pairRopeContacts_.assign(pairRopes_.size(), PairRopeContacts{});
  const auto count = [&](const RopeObject& rope, const RopePairContactRecord& record) {
    const int k = pairRopeIndex_[static_cast<std::size_t>(rope.worldIndex_)];
    if (k < 0) return;
    PairRopeContacts& counts = pairRopeContacts_[static_cast<std::size_t>(k)];
    counts.overlap = std::max(counts.overlap, record.depth);
    ++counts.near;
    if (record.active) ++counts.active;
  };
  for (const RopePairContactRecord& record : report_.ropeContacts) {
    count(*record.ropeA, record);
    if (record.ropeB != record.ropeA) count(*record.ropeB, record);  // self-contact counts once
  }
  for (std::size_t k = 0; k < pairRopes_.size(); ++k) {
    const PairRopeContacts& counts = pairRopeContacts_[k];
    pairRopes_[k]->recordRopeContacts(counts.active, counts.overlap, counts.near > 0);
  }
  report_.ropeContactSeconds =
      findSeconds_ + std::chrono::duration<double>(std::chrono::steady_clock::now() - ropeStart).count();
}

void RopeWorld::failRopeContacts(const char* message) {
  // The coupled solve may have corrected some trials and not others: every rope of the solve that
  // still has a trial drops it and keeps its state this substep.
  ++warnings_.ropeContactFailures;
  lastError_ = message;
  ropeRopeContacts_.forgetAll();
  report_.ropeContacts.clear();
  report_.ropeContactFailure = "an exception was thrown in the rope-rope contact solve; the ropes kept their state";
  // Only the ropes the pairs name took part in the solve; the others' trials are their own.
  for (RopeObject* rope : pairRopes_) {
    if (rope->rod().hasTrial()) rope->failSubstep(message);
  }
}

void RopeWorld::runCallback() {
  if (!callback_) return;
  guardedCall([&] { callback_(report_); },
              [&](const char* message) {
                ++warnings_.callbackExceptions;
                lastError_ = message;
              });
}

void RopeWorld::recoverFromException(const char* message) noexcept {
  ++warnings_.exceptions;
  try {
    lastError_ = message;
  } catch (...) {
    // out of memory for the message: the count is what matters
  }
  report_.failure = "an exception was thrown in the ropes' substep; the ropes kept their state (RopeWorld::lastError())";
  for (RopeObject* rope : ropes_) {
    if (!rope->rod().hasTrial()) continue;
    try {
      rope->failSubstep(message);
    } catch (...) {
      rope->rod().clearLoads();  // cannot throw: at least the trial is gone
    }
  }
}

}  // namespace rope::bullet
