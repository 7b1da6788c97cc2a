// SPDX-License-Identifier: MIT
#pragma once
// The rope's collision proxy in Bullet's broadphase: capsules of the rope's radius over equal
// parameter pieces of every knot span (capsulesPerSpan per span, rebuilt after knot insertions and
// removals). Each capsule is a btCollisionObject whose axis-aligned box covers the capsule at the
// start of the coming step and at its predicted end (positions + h * velocity), padded by the radius,
// the speculative margin and the curve's bulge over the chord, so Bullet's broadphase finds every
// body the capsule can touch during the step (swept boxes). The objects carry CF_NO_CONTACT_RESPONSE
// and a collision shape for which Bullet's dispatcher runs no narrowphase, so Bullet's solver never
// sees them: all rope contact goes through the bridge's own narrowphase and response.

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>

#include <memory>
#include <vector>

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/capsule.h"
#include "bullet_bridge/swept_box_shape.h"
#include "rope/rod/rod.h"

namespace rope::bullet {

class RopeObject;

// userIndex2 of every dynamic rope capsule: tells rope capsules from the user's objects (userPointer is
// the RopeObject, userIndex the capsule index).
constexpr int kRopeCapsuleTag = 0x526f7065;  // "Rope"

struct CapsuleProxy {
  double s0 = 0.0, s1 = 0.0;                  // curve parameters of the capsule's axis ends
  std::unique_ptr<SweptBoxShape> shape;       // the swept box (see the header comment)
  std::unique_ptr<btCollisionObject> object;  // registered in the world's broadphase
};

class CapsuleProxies {
 public:
  CapsuleProxies(RopeObject& owner, int capsulesPerSpan, double radius);
  ~CapsuleProxies();
  CapsuleProxies(const CapsuleProxies&) = delete;
  CapsuleProxies& operator=(const CapsuleProxies&) = delete;

  // Registers every capsule in world's broadphase with the given filter / removes them again.
  // removeFromWorld leaves the world alone if it was destroyed already (orphaned()).
  void addToWorld(btCollisionWorld& world, int group, int mask);
  void removeFromWorld();
  // True if the capsules were added to a world and every one has since lost its broadphase handle:
  // Bullet's btCollisionWorld destructor clears the handles of the objects still in it, so the world
  // was destroyed (or someone removed every capsule by hand) and must not be touched any more.
  bool orphaned() const;

  // Follows the rod's current knots (adds or removes capsules) and evaluates the capsule axes.
  void rebuild(const Rod& rod);
  // Rebuilds, then sets each box to cover the capsule now and after predictionTime (s) of the rod's
  // current velocities, padded by margin (m), and tells the broadphase. A box Bullet would drop as too
  // large (diagonal^2 >= 1e12 m^2, its "overflow in AABB" rule) is not applied; the count is returned.
  int updateBoxes(const Rod& rod, double predictionTime, double margin);

  int size() const { return static_cast<int>(proxies_.size()); }
  const CapsuleProxy& proxy(int i) const { return proxies_[static_cast<std::size_t>(i)]; }
  // Capsule i at the rod state of the last rebuild, world frame.
  Capsule capsule(int i) const;

  // The rope a collision object stands in for, or nullptr if it is not a rope capsule.
  static RopeObject* ropeOf(const btCollisionObject& object);
  // Index of the capsule within its rope (valid only if ropeOf(object) != nullptr).
  static int capsuleIndexOf(const btCollisionObject& object) { return object.getUserIndex(); }

 private:
  RopeObject& owner_;
  int capsulesPerSpan_;
  btScalar radius_;
  std::vector<CapsuleProxy> proxies_;
  std::vector<btVector3> axis_;  // size() + 1 axis points at the last rebuild
  btCollisionWorld* world_ = nullptr;
  int group_ = 0, mask_ = 0;
};

}  // namespace rope::bullet
