// SPDX-License-Identifier: MIT
#pragma once
// How a rope's broadphase pairs reach the bridge instead of Bullet's narrowphase (capsule_proxies.h).
//
// A RopeWorld installs, on its world's btCollisionDispatcher, a collision create function for every
// contact-point pair (COMPOUND_SHAPE_PROXYTYPE, X) and (X, COMPOUND_SHAPE_PROXYTYPE). For a pair whose
// top-level object is a rope it creates a RopePairAlgorithm, which computes nothing and makes no
// manifold: it lists its pair in the rope's RopeWorld's RopePairs from the pair's first dispatch
// until Bullet drops the pair (and destroys the algorithm with it: boxes apart, an object removed,
// the world destroyed). The RopeWorld's substep reads that list, re-checking each pair's overlap (the
// pair cache drops pairs lazily). Every other pair, compounds of the user's included, goes to the
// create function that was in the dispatcher before (restored when the RopeWorld goes). Queries that
// reach a rope's capsules (contactTest, contactPairTest) are the CapsuleDispatch's, which the
// RopeDispatch holds (capsule_dispatch.h; kinematic ropes share it), so those run Bullet's own
// algorithms over the rope's capsules.
//
// Why create functions and not a near callback: a btNearCallback is a plain function pointer with no
// user data, so chaining the user's callback would need a global registry, and a dispatch table
// entry is what btSoftBody uses. Why not scan the pair cache: the list holds only the ropes' pairs,
// where a scan visits every body-body pair too.
//
// Registering create functions for compound pairs on the same dispatcher while a RopeWorld exists
// replaces (or, if they wrap the one found there, captures) the rope's: do it before creating the
// RopeWorld or after destroying it.
// Not API: installed only because rope_world.h holds a RopeDispatch and RopePairs; may change in any
// release.

#include <BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btCollisionCreateFunc.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>

#include <memory>
#include <vector>

#include "bullet_bridge/bullet_precision.h"

namespace rope::bullet {

class RopePairAlgorithm;
class CapsuleDispatch;  // capsule_dispatch.h (internal)

// The rope pairs Bullet keeps (at least one of the two objects is a rope's), in no fixed order.
class RopePairs {
 public:
  RopePairs() = default;
  ~RopePairs();
  RopePairs(const RopePairs&) = delete;
  RopePairs& operator=(const RopePairs&) = delete;

  void add(RopePairAlgorithm& algorithm);
  // The algorithm is destroyed (its pair left the cache). O(1).
  void remove(RopePairAlgorithm& algorithm);
  // Calls f(object0, object1) for every pair listed.
  template <class F>
  void forEach(F&& f) const;

 private:
  std::vector<RopePairAlgorithm*> pairs_;
};

class RopePairAlgorithm : public btCollisionAlgorithm {
 public:
  // Lists the pair in the rope's RopeWorld (if the rope is in one).
  RopePairAlgorithm(const btCollisionAlgorithmConstructionInfo& info, const btCollisionObject& object0,
                    const btCollisionObject& object1);
  ~RopePairAlgorithm() override;
  void processCollision(const btCollisionObjectWrapper*, const btCollisionObjectWrapper*, const btDispatcherInfo&,
                        btManifoldResult*) override {}
  btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                 btManifoldResult*) override {
    return btScalar(1);
  }
  void getAllContactManifolds(btManifoldArray&) override {}

 private:
  friend class RopePairs;
  const btCollisionObject* object0_;
  const btCollisionObject* object1_;
  RopePairs* list_ = nullptr;  // where it is listed, or nullptr
  int slot_ = -1;
};

// The create functions of one RopeWorld, installed in the constructor and the dispatcher's previous
// entries restored in the destructor (unless detach() said the world is gone).
class RopeDispatch {
 public:
  // Throws InvalidArgument("world", ...) if the world's dispatcher is not a btCollisionDispatcher or
  // already routes rope pairs (a second RopeWorld on one Bullet world).
  explicit RopeDispatch(btCollisionWorld& world);
  ~RopeDispatch();
  RopeDispatch(const RopeDispatch&) = delete;
  RopeDispatch& operator=(const RopeDispatch&) = delete;
  // The Bullet world (and perhaps its dispatcher) was destroyed: leave it alone from now on.
  void detach();

 private:
  class CreateFunc;
  btCollisionDispatcher* dispatcher_;
  std::vector<std::unique_ptr<CreateFunc>> funcs_;
  std::shared_ptr<CapsuleDispatch> capsules_;
};

template <class F>
void RopePairs::forEach(F&& f) const {
  for (const RopePairAlgorithm* algorithm : pairs_) f(algorithm->object0_, algorithm->object1_);
}

}  // namespace rope::bullet
