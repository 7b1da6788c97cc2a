// SPDX-License-Identifier: MIT
#include "bullet_bridge/collision_object/rope_dispatch.h"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>

#include <new>

#include "bullet_bridge/capsule_proxies.h"
#include "bullet_bridge/collision_object/capsule_dispatch.h"
#include "bullet_bridge/rope_object.h"
#include "bullet_bridge/rope_world.h"
#include "rope/common/error.h"

namespace rope::bullet {

namespace {

// The wrapper stands for a rope's object as a whole (not one of its capsule children, which Bullet's
// compound algorithm dispatches on their own when it runs for a query: capsule_dispatch.h).
bool isWholeRope(const btCollisionObjectWrapper* wrapper) {
  const btCollisionObject* object = wrapper->getCollisionObject();
  return CapsuleProxies::ropeOf(*object) != nullptr && wrapper->getCollisionShape() == object->getCollisionShape();
}

}  // namespace

class RopeDispatch::CreateFunc : public btCollisionAlgorithmCreateFunc {
 public:
  CreateFunc(int type0, int type1, btCollisionAlgorithmCreateFunc* previous)
      : type0(type0), type1(type1), previous(previous) {}
  btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                 const btCollisionObjectWrapper* body0,
                                                 const btCollisionObjectWrapper* body1) override {
    if (isWholeRope(body0) || isWholeRope(body1)) {
      void* memory = info.m_dispatcher1->allocateCollisionAlgorithm(sizeof(RopePairAlgorithm));
      return new (memory) RopePairAlgorithm(info, *body0->getCollisionObject(), *body1->getCollisionObject());
    }
    return previous != nullptr ? previous->CreateCollisionAlgorithm(info, body0, body1) : nullptr;
  }
  const int type0, type1;
  btCollisionAlgorithmCreateFunc* const previous;
};

RopePairs::~RopePairs() {
  for (RopePairAlgorithm* algorithm : pairs_) {
    algorithm->list_ = nullptr;
    algorithm->slot_ = -1;
  }
}

void RopePairs::add(RopePairAlgorithm& algorithm) {
  algorithm.list_ = this;
  algorithm.slot_ = static_cast<int>(pairs_.size());
  pairs_.push_back(&algorithm);
}

void RopePairs::remove(RopePairAlgorithm& algorithm) {
  const auto slot = static_cast<std::size_t>(algorithm.slot_);
  pairs_[slot] = pairs_.back();
  pairs_[slot]->slot_ = static_cast<int>(slot);
  pairs_.pop_back();
  algorithm.list_ = nullptr;
  algorithm.slot_ = -1;
}

RopePairAlgorithm::RopePairAlgorithm(const btCollisionAlgorithmConstructionInfo& info,
                                     const btCollisionObject& object0, const btCollisionObject& object1)
    : btCollisionAlgorithm(info), object0_(&object0), object1_(&object1) {
  RopeObject* rope = CapsuleProxies::ropeOf(object0);
  if (rope == nullptr) rope = CapsuleProxies::ropeOf(object1);
  if (rope != nullptr && rope->world() != nullptr) rope->world()->ropePairs_.add(*this);
}

RopePairAlgorithm::~RopePairAlgorithm() {
  if (list_ != nullptr) list_->remove(*this);
}

RopeDispatch::RopeDispatch(btCollisionWorld& world) : dispatcher_(dynamic_cast<btCollisionDispatcher*>(world.getDispatcher())) {
  if (dispatcher_ == nullptr) {
    throw InvalidArgument("world", "its dispatcher", "must be a btCollisionDispatcher (or derived from one)");
  }
  if (dynamic_cast<CreateFunc*>(dispatcherEntry(*dispatcher_, COMPOUND_SHAPE_PROXYTYPE, COMPOUND_SHAPE_PROXYTYPE, false)) !=
      nullptr) {
    throw InvalidArgument("world", "has a RopeWorld already", "one RopeWorld per Bullet world");
  }
  // Queries that reach a rope's capsules (capsule_dispatch.h); shared with kinematic ropes. Taken first,
  // so that the entries below wrap it where both concern a pair (a rope capsule against a compound).
  capsules_ = CapsuleDispatch::acquire(world);
  // Contact points of a whole rope (its compound) against every type.
  const auto add = [this](int type0, int type1) {
    for (const auto& func : funcs_)
      if (func->type0 == type0 && func->type1 == type1) return;
    funcs_.push_back(std::make_unique<CreateFunc>(type0, type1, dispatcherEntry(*dispatcher_, type0, type1, false)));
  };
  for (int other = 0; other < MAX_BROADPHASE_COLLISION_TYPES; ++other) {
    add(COMPOUND_SHAPE_PROXYTYPE, other);
    add(other, COMPOUND_SHAPE_PROXYTYPE);
  }
  for (const auto& func : funcs_) setDispatcherEntry(*dispatcher_, func->type0, func->type1, false, func.get());
}

RopeDispatch::~RopeDispatch() {
  if (dispatcher_ == nullptr) return;
  for (const auto& func : funcs_) {
    // Only our own entries: one the user registered since is theirs to keep.
    if (dispatcherEntry(*dispatcher_, func->type0, func->type1, false) == func.get()) {
      setDispatcherEntry(*dispatcher_, func->type0, func->type1, false, func->previous);
    }
  }
}

void RopeDispatch::detach() {
  dispatcher_ = nullptr;
  if (capsules_) capsules_->detach();
}

}  // namespace rope::bullet
