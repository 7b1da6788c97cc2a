// SPDX-License-Identifier: MIT
#include "bullet_bridge/collision_object/capsule_dispatch.h"

#include <BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btCollisionCreateFunc.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>

#include <new>
#include <optional>

#include "bullet_bridge/collision_object/rope_shape.h"

namespace rope::bullet {

namespace {

constexpr int kCapsuleType = FAST_CONCAVE_MESH_PROXYTYPE;  // RopeCapsuleShape (rope_shape.h)

// A pointer to a protected base member formed in a derived class is an ordinary member pointer.
struct DispatcherTable : btCollisionDispatcher {
  static btCollisionAlgorithmCreateFunc* get(btCollisionDispatcher& dispatcher, int type0, int type1, bool closest) {
    constexpr auto contact = &DispatcherTable::m_doubleDispatchContactPoints;
    constexpr auto closestPoints = &DispatcherTable::m_doubleDispatchClosestPoints;
    return closest ? (dispatcher.*closestPoints)[type0][type1] : (dispatcher.*contact)[type0][type1];
  }
};

bool isRopeCapsule(const btCollisionObjectWrapper* wrapper) {
  return dynamic_cast<const RopeCapsuleShape*>(wrapper->getCollisionShape()) != nullptr;
}

// Bullet's own algorithm for the same capsule as a btCapsuleShape (rope_shape.h says why the child is
// not one), built per call.
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

btCollisionAlgorithmCreateFunc* dispatcherEntry(btCollisionDispatcher& dispatcher, int type0, int type1, bool closest) {
  return DispatcherTable::get(dispatcher, type0, type1, closest);
}

void setDispatcherEntry(btCollisionDispatcher& dispatcher, int type0, int type1, bool closest,
                        btCollisionAlgorithmCreateFunc* func) {
  if (closest) {
    dispatcher.registerClosestPointsCreateFunc(type0, type1, func);
  } else {
    dispatcher.registerCollisionCreateFunc(type0, type1, func);
  }
}

class CapsuleDispatch::CreateFunc : public btCollisionAlgorithmCreateFunc {
 public:
  CreateFunc(CapsuleDispatch& owner, int type0, int type1, bool closest, btCollisionAlgorithmCreateFunc* previous)
      : owner(owner), type0(type0), type1(type1), closest(closest), previous(previous) {}
  btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                 const btCollisionObjectWrapper* body0,
                                                 const btCollisionObjectWrapper* body1) override {
    if (isRopeCapsule(body0) || isRopeCapsule(body1)) {
      void* memory = info.m_dispatcher1->allocateCollisionAlgorithm(sizeof(CapsuleStandInAlgorithm));
      return new (memory)
          CapsuleStandInAlgorithm(info, closest ? BT_CLOSEST_POINT_ALGORITHMS : BT_CONTACT_POINT_ALGORITHMS);
    }
    return previous != nullptr ? previous->CreateCollisionAlgorithm(info, body0, body1) : nullptr;
  }
  CapsuleDispatch& owner;
  const int type0, type1;
  const bool closest;
  btCollisionAlgorithmCreateFunc* const previous;
};

std::shared_ptr<CapsuleDispatch> CapsuleDispatch::acquire(btCollisionWorld& world) {
  auto* dispatcher = dynamic_cast<btCollisionDispatcher*>(world.getDispatcher());
  if (dispatcher == nullptr) return nullptr;
  if (auto* installed = dynamic_cast<CreateFunc*>(dispatcherEntry(*dispatcher, kCapsuleType, BOX_SHAPE_PROXYTYPE, false))) {
    if (std::shared_ptr<CapsuleDispatch> shared = installed->owner.self_.lock()) return shared;
  }
  std::shared_ptr<CapsuleDispatch> dispatch(new CapsuleDispatch(*dispatcher));
  dispatch->self_ = dispatch;
  return dispatch;
}

CapsuleDispatch::CapsuleDispatch(btCollisionDispatcher& dispatcher) : dispatcher_(&dispatcher) {
  const auto add = [this](int type0, int type1, bool closest) {
    for (const auto& func : funcs_)
      if (func->type0 == type0 && func->type1 == type1 && func->closest == closest) return;
    funcs_.push_back(
        std::make_unique<CreateFunc>(*this, type0, type1, closest, dispatcherEntry(*dispatcher_, type0, type1, closest)));
  };
  for (int other = 0; other < MAX_BROADPHASE_COLLISION_TYPES; ++other) {
    for (const bool closest : {false, true}) {
      add(kCapsuleType, other, closest);
      add(other, kCapsuleType, closest);
    }
  }
  for (const auto& func : funcs_) setDispatcherEntry(*dispatcher_, func->type0, func->type1, func->closest, func.get());
}

CapsuleDispatch::~CapsuleDispatch() {
  if (dispatcher_ == nullptr) return;
  for (const auto& func : funcs_) {
    // Only our own entries: one registered since (by the user) is theirs to keep.
    if (dispatcherEntry(*dispatcher_, func->type0, func->type1, func->closest) == func.get()) {
      setDispatcherEntry(*dispatcher_, func->type0, func->type1, func->closest, func->previous);
    }
  }
}

}  // namespace rope::bullet
