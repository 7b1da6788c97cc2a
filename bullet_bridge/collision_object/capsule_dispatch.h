// SPDX-License-Identifier: MIT
#pragma once
// How Bullet's own contact queries meet a rope's capsules (rope_shape.h): contactTest and
// contactPairTest reach them through Bullet's compound algorithm, which looks up an algorithm for each
// child in the dispatcher's tables. A RopeCapsuleShape child has the concave type
// FAST_CONCAVE_MESH_PROXYTYPE, whose stock entry is Bullet's convex-concave algorithm: that would meet
// the capsule as its 16-sided triangle mesh, up to 2 % of the radius inside the true surface. A
// CapsuleDispatch takes, in both of the dispatcher's tables (contact points and closest points), the
// entries of that type against every other; for a pair with a rope capsule it runs the algorithm
// Bullet would run for a btCapsuleShape of the same size in its place (exact capsule contact), and
// every other pair goes to the entry that was there before.
//
// One per dispatcher, shared: everything that puts rope capsules into a Bullet world (a RopeWorld, a
// KinematicRope in a world without one) holds it while it is there; the last holder to let go puts
// the previous entries back (unless the dispatcher is gone: detach()). So a kinematic rope's
// contacts in Bullet's queries are exact with or without a RopeWorld, and a RopeWorld and kinematic
// ropes come and go in any order.
// Internal: not installed.

#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>

#include <memory>
#include <vector>

namespace rope::bullet {

class CapsuleDispatch {
 public:
  // The dispatch on the world's dispatcher, installed now if none is. nullptr if the dispatcher is not
  // a btCollisionDispatcher (then Bullet's queries meet the capsule mesh).
  static std::shared_ptr<CapsuleDispatch> acquire(btCollisionWorld& world);
  ~CapsuleDispatch();
  CapsuleDispatch(const CapsuleDispatch&) = delete;
  CapsuleDispatch& operator=(const CapsuleDispatch&) = delete;
  // The Bullet world (and perhaps its dispatcher) was destroyed: leave it alone from now on, for every
  // holder.
  void detach() { dispatcher_ = nullptr; }

 private:
  class CreateFunc;
  explicit CapsuleDispatch(btCollisionDispatcher& dispatcher);
  btCollisionDispatcher* dispatcher_;
  std::vector<std::unique_ptr<CreateFunc>> funcs_;
  std::weak_ptr<CapsuleDispatch> self_;  // what acquire() hands the next holder
};

// Reads a dispatcher's current table entry (protected in Bullet, with no getter). closest: the
// closest-points table, else the contact-points table.
btCollisionAlgorithmCreateFunc* dispatcherEntry(btCollisionDispatcher& dispatcher, int type0, int type1, bool closest);
// Writes it (Bullet's registerCollisionCreateFunc / registerClosestPointsCreateFunc).
void setDispatcherEntry(btCollisionDispatcher& dispatcher, int type0, int type1, bool closest,
                        btCollisionAlgorithmCreateFunc* func);

}  // namespace rope::bullet
