// SPDX-License-Identifier: MIT
#include "bullet_bridge/collision_object/rope_dispatch.h"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>

#include <new>
#include <optional>

#include "bullet_bridge/capsule_proxies.h"
#include "bullet_bridge/collision_object/rope_shape.h"
#include "bullet_bridge/rope_object.h"
#include "bullet_bridge/rope_world.h"
#include "rope/common/error.h"

namespace rope::bullet {

namespace {

// Reads the dispatcher's current contact-point table (protected in Bullet, with no getter): a
// pointer to a protected base member formed in a derived class is an ordinary member pointer.
struct DispatcherTable : btCollisionDispatcher {
  static btCollisionAlgorithmCreateFunc* get(btCollisionDispatcher& dispatcher, int type0, int type1) {
    constexpr auto table = &DispatcherTable::m_doubleDispatchContactPoints;
    return (dispatcher.*table)[type0][type1];
  }
  static btCollisionAlgorithmCreateFunc* getClosest(btCollisionDispatcher& dispatcher, int type0, int type1) {
    constexpr auto table = &DispatcherTable::m_doubleDispatchClosestPoints;
    return (dispatcher.*table)[type0][type1];
  }
};

// The wrapper stands for a rope's object as a whole (not one of its capsule children, which Bullet's
// compound algorithm dispatches on their own when it runs for a query).
bool isWholeRope(const btCollisionObjectWrapper* wrapper) {
  const btCollisionObject* object = wrapper->getCollisionObject();
  return CapsuleProxies::ropeOf(*object) != nullptr && wrapper->getCollisionShape() == object->getCollisionShape();
}

bool isRopeCapsule(const btCollisionObjectWrapper* wrapper) {
  return dynamic_cast<const RopeCapsuleShape*>(wrapper->getCollisionShape()) != nullptr;
}

// A query (contactTest, contactPairTest) that reaches a rope's capsule: Bullet's own algorithm for the
// same capsule as a btCapsuleShape (rope_shape.h says why the child is not one), built per call.
class CapsuleStandInAlgorithm : public btCollisionAlgorithm {
 public:
  // queryType: the table the stand-in's algorithm comes from (the one this algorithm was found in);
  // a shared manifold (the compound's, for contact points) is handed on.
  CapsuleStandInAlgorithm(const btCollisionAlgorithmConstructionInfo& info, ebtDispatcherQueryType queryType)
      : btCollisionAlgorithm(info), queryType_(queryType), sharedManifold_(info.m_manifold) {}
  void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                        const btDispatcherInfo& info, btManifoldResult* result) override {
    const auto* capsule0 = dynamic_cast<const RopeCapsuleShape*>(body0->getCollisionShape());
    const auto* capsule1 = dynamic_cast<const RopeCapsuleShape*>(body1->getCollisionShape());
    std::optional<btCapsuleShape> standIn0, standIn1;
    if (capsule0 != nullptr) standIn0.emplace(capsule0->standIn());
    if (capsule1 != nullptr) standIn1.emplace(capsule1->standIn());
    const btCollisionObjectWrapper wrap0(body0->m_parent, standIn0 ? &*standIn0 : body0->getCollisionShape(),
                                         body0->getCollisionObject(), body0->getWorldTransform(), body0->m_partId,
                                         body0->m_index);
    const btCollisionObjectWrapper wrap1(body1->m_parent, standIn1 ? &*standIn1 : body1->getCollisionShape(),
                                         body1->getCollisionObject(), body1->getWorldTransform(), body1->m_partId,
                                         body1->m_index);
    // The result reads the shapes and objects through its wrappers: point them at the stand-ins for
    // the call, and give back what the caller had (the delegate sets its own manifold on the result).
    const btCollisionObjectWrapper* saved0 = result->getBody0Wrap();
    const btCollisionObjectWrapper* saved1 = result->getBody1Wrap();
    btPersistentManifold* savedManifold = result->getPersistentManifold();
    if (saved0 == body0) result->setBody0Wrap(&wrap0);
    if (saved0 == body1) result->setBody0Wrap(&wrap1);
    if (saved1 == body1) result->setBody1Wrap(&wrap1);
    if (saved1 == body0) result->setBody1Wrap(&wrap0);
    btCollisionAlgorithm* delegate = m_dispatcher->findAlgorithm(&wrap0, &wrap1, sharedManifold_, queryType_);
    if (delegate != nullptr) {
      delegate->processCollision(&wrap0, &wrap1, info, result);
      delegate->~btCollisionAlgorithm();
      m_dispatcher->freeCollisionAlgorithm(delegate);
    }
    result->setBody0Wrap(saved0);
    result->setBody1Wrap(saved1);
    result->setPersistentManifold(savedManifold);
  }
  btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                 btManifoldResult*) override {
    return btScalar(1);
  }
  void getAllContactManifolds(btManifoldArray&) override {}

 private:
  ebtDispatcherQueryType queryType_;
  btPersistentManifold* sharedManifold_;
};

}  // namespace

class RopeDispatch::CreateFunc : public btCollisionAlgorithmCreateFunc {
 public:
  // closest: an entry of the closest-point table, else of the contact-point table.
  CreateFunc(int type0, int type1, bool closest, btCollisionAlgorithmCreateFunc* previous)
      : type0(type0), type1(type1), closest(closest), previous(previous) {}
  btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                 const btCollisionObjectWrapper* body0,
                                                 const btCollisionObjectWrapper* body1) override {
    if (!closest && (isWholeRope(body0) || isWholeRope(body1))) {
      void* memory = info.m_dispatcher1->allocateCollisionAlgorithm(sizeof(RopePairAlgorithm));
      return new (memory) RopePairAlgorithm(info, *body0->getCollisionObject(), *body1->getCollisionObject());
    }
    if (isRopeCapsule(body0) || isRopeCapsule(body1)) {
      void* memory = info.m_dispatcher1->allocateCollisionAlgorithm(sizeof(CapsuleStandInAlgorithm));
      return new (memory)
          CapsuleStandInAlgorithm(info, closest ? BT_CLOSEST_POINT_ALGORITHMS : BT_CONTACT_POINT_ALGORITHMS);
    }
    return previous != nullptr ? previous->CreateCollisionAlgorithm(info, body0, body1) : nullptr;
  }
  // The table entry this function occupies, and what it held before.
  btCollisionAlgorithmCreateFunc* current(btCollisionDispatcher& dispatcher) const {
    return closest ? DispatcherTable::getClosest(dispatcher, type0, type1) : DispatcherTable::get(dispatcher, type0, type1);
  }
  void install(btCollisionDispatcher& dispatcher, btCollisionAlgorithmCreateFunc* func) const {
    if (closest) {
      dispatcher.registerClosestPointsCreateFunc(type0, type1, func);
    } else {
      dispatcher.registerCollisionCreateFunc(type0, type1, func);
    }
  }
  const int type0, type1;
  const bool closest;
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
  if (dynamic_cast<CreateFunc*>(DispatcherTable::get(*dispatcher_, COMPOUND_SHAPE_PROXYTYPE, COMPOUND_SHAPE_PROXYTYPE)) !=
      nullptr) {
    throw InvalidArgument("world", "has a RopeWorld already", "one RopeWorld per Bullet world");
  }
  // Contact points: a whole rope (its compound) and a rope's capsule (queries reach the capsules
  // through Bullet's compound algorithm, which dispatches its children from this table unless the
  // query asks for a distance threshold); closest points: a rope's capsule.
  constexpr int kCapsule = FAST_CONCAVE_MESH_PROXYTYPE;  // RopeCapsuleShape
  const auto add = [this](int type0, int type1, bool closest) {
    for (const auto& func : funcs_)
      if (func->type0 == type0 && func->type1 == type1 && func->closest == closest) return;
    btCollisionAlgorithmCreateFunc* previous =
        closest ? DispatcherTable::getClosest(*dispatcher_, type0, type1) : DispatcherTable::get(*dispatcher_, type0, type1);
    funcs_.push_back(std::make_unique<CreateFunc>(type0, type1, closest, previous));
  };
  for (int other = 0; other < MAX_BROADPHASE_COLLISION_TYPES; ++other) {
    for (const int type : {static_cast<int>(COMPOUND_SHAPE_PROXYTYPE), kCapsule}) {
      add(type, other, false);
      add(other, type, false);
    }
    add(kCapsule, other, true);
    add(other, kCapsule, true);
  }
  for (const auto& func : funcs_) func->install(*dispatcher_, func.get());
}

RopeDispatch::~RopeDispatch() {
  if (dispatcher_ == nullptr) return;
  for (const auto& func : funcs_) {
    // Only our own entries: one the user registered since is theirs to keep.
    if (func->current(*dispatcher_) == func.get()) func->install(*dispatcher_, func->previous);
  }
}

}  // namespace rope::bullet
