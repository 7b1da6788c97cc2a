// SPDX-License-Identifier: MIT
#pragma once
// The one collision object of a rope in Bullet's world, for dynamic ropes (RopeObject) and kinematic
// tractrix ropes (KinematicRope) alike. Its shape (rope_shape.h) is a compound of capsules of the
// rope's radius over equal parameter pieces of every knot span (capsulesPerSpan per span; capsules are
// added and removed at the end as knots come and go, so child index = capsule index along the rope),
// and the compound's btDbvt is the rope's midphase tree.
//
// Why one object per rope and not one per capsule (issue 14): Bullet widens every broadphase box by
// its contact breaking threshold, so per-capsule boxes paired every capsule with dozens of a
// neighbouring rope's and the pair cache grew with the number of capsules near each other; Bullet's
// own queries could not see the capsules either. This is btSoftBody's model: one broadphase box per
// body, a tree of its parts inside. Why a btCompoundShape for that tree: its dynamic AABB tree is
// exactly such a btDbvt, and every query of btCollisionWorld (rayTest, contactTest, contactPairTest,
// convexSweepTest) already walks compounds child by child, so ropes show up in them with no query
// code of ours. The leaves are swept boxes, not the capsules' tight boxes: each covers the capsule
// over the coming step (a dynamic rope: positions + h * velocity, in every direction) or over the
// step just made (a kinematic rope: where the capsule was and is), padded by the radius and the
// curve's bulge over the chord, and kept a little fatter (kLeafSlack) so that a rope at rest never
// touches its tree. A kinematic rope's leaves also carry its speculative margin. A dynamic rope's
// carry only the rope-rope share of it (0.55 radii; capsule_proxies.cpp, kRopeReachShare), and the
// rest of its margin is added to the object's broadphase box (the tree's root) and to every body
// query (capsulesOverlapping), so that a knot's tree-against-tree search meets fewer distant pairs
// while bodies still meet every capsule within the margin. The
// object carries CF_STATIC_OBJECT | CF_NO_CONTACT_RESPONSE and stays active (DISABLE_DEACTIVATION).
// A dynamic rope's pairs go to the bridge through Bullet's dispatcher (rope_dispatch.h), which runs
// no narrowphase or solver contact for them. A kinematic rope finds the bodies it pushes itself
// (kinematic_rope.h), so its object asks Bullet for no pair except with a dynamic rope's object
// (btCollisionObject::checkCollideWithOverride): Bullet's dispatcher makes no algorithm, manifold or
// contact for it, and its queries still see its capsules.

#include <BulletCollision/BroadphaseCollision/btDbvt.h>
#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/capsule.h"
#include "bullet_bridge/collision_object/rope_shape.h"
#include "rope/rod/rod.h"

namespace rope::bullet {

class RopeObject;

// userIndex2 of every dynamic rope's collision object: tells ropes from the user's objects
// (userPointer is the RopeObject). A kinematic rope's object carries kKinematicRopeTag
// (kinematic_rope.h) and points to the KinematicRope.
constexpr int kRopeCapsuleTag = 0x526f7065;  // "Rope"
// userIndex2 of every kinematic rope's collision object; userPointer is the KinematicRope.
constexpr int kKinematicRopeTag = 0x4b526f70;  // "KRop"

// The capsule ends' curve parameters, into `ends` (cleared first): every non-empty knot span of
// [begin, end] cut into `pieces` equal parameter pieces.
void capsuleEnds(const KnotVector& knots, double begin, double end, int pieces, std::vector<double>& ends);

struct CapsuleProxy {
  double s0 = 0.0, s1 = 0.0;            // curve parameters of the capsule's axis ends
  btCollisionObject* object = nullptr;  // the rope's collision object (shared by all its capsules)
};

class CapsuleProxies {
 public:
  // What the object stands for: a dynamic rope's proxies ...
  CapsuleProxies(RopeObject& owner, int capsulesPerSpan, double radius);
  // ... or, with tag kKinematicRopeTag, a kinematic rope's (pairs with dynamic ropes' objects only).
  CapsuleProxies(void* owner, int tag, double radius);
  ~CapsuleProxies();
  CapsuleProxies(const CapsuleProxies&) = delete;
  CapsuleProxies& operator=(const CapsuleProxies&) = delete;

  // Registers the rope's object in world's broadphase with the given filter / removes it again.
  // removeFromWorld leaves the world alone if it was destroyed already (orphaned()).
  void addToWorld(btCollisionWorld& world, int group, int mask);
  void removeFromWorld();
  // True if the object was added to a world and has since lost its broadphase handle: Bullet's
  // btCollisionWorld destructor clears the handles of the objects still in it, so the world was
  // destroyed (or someone removed the object by hand) and must not be touched any more.
  bool orphaned() const;
  // The broadphase filter of the object (in the world: its broadphase proxy's too).
  void setFilter(int group, int mask);

  // Follows the rod's current knots (adds or removes capsules) and evaluates the capsule axes (the
  // compound's children follow in updateBoxes). From the same knots and control points as the last
  // rebuild, the capsules stay as they are (nothing to evaluate).
  void rebuild(const Rod& rod);
  // The same from capsule ends computed by the caller (capsuleEnds) and the curve's points at them.
  // Throws InvalidArgument("ends") for fewer than 2 ends, ("axis") unless axis.size() == ends.size(),
  // and changes nothing then.
  void rebuild(const std::vector<double>& ends, const std::vector<btVector3>& axis);
  // Rebuilds, places the compound's capsule children, then sets each capsule's tree leaf to cover the capsule now and after predictionTime
  // (s) of the rod's current velocities, padded as the header says for a speculative margin of
  // `margin` (m), and the object's box to the tree's root grown by the rest of the margin. A leaf Bullet would drop as too large (diagonal^2 >= 1e12 m^2, its "overflow in AABB"
  // rule) is not applied; the count is returned (all capsules if the whole rope's box is too large).
  int updateBoxes(const Rod& rod, double predictionTime, double margin);
  // The same, but the object's new box reaches Bullet's broadphase only at the next
  // announceObjectBox(): a RopeWorld finishes some ropes' substeps out of world order and hands their
  // boxes to the broadphase in world order afterwards, which keeps the broadphase's tree, and so
  // Bullet's pair order, as it was (rope_world.cpp, substep).
  int updateBoxesDeferred(const Rod& rod, double predictionTime, double margin);
  // Hands the box of the last updateBoxesDeferred to Bullet's broadphase, if it has not been yet.
  void announceObjectBox();
  // The parts of updateBoxes, for a caller that computes its own swept boxes: placeCapsule moves
  // compound child i onto capsule i's axis; fitLeaf sets its tree leaf to cover [lo, hi] (false, and
  // the leaf kept, if Bullet would drop such a box); fitObjectBox sets the object's broadphase box to
  // the tree's root (false, and the box kept, if too large). placeCapsule and fitLeaf throw
  // InvalidArgument("i") for an index that names no capsule.
  void placeCapsule(int i);
  bool fitLeaf(int i, const btVector3& lo, const btVector3& hi);
  bool fitObjectBox();

  int size() const { return static_cast<int>(proxies_.size()); }
  const CapsuleProxy& proxy(int i) const { return proxies_[static_cast<std::size_t>(i)]; }
  // Capsule i at the rod state of the last rebuild, world frame.
  Capsule capsule(int i) const;
  // The speed |C'(s)| (m/s) at each capsule end, size() + 1 values in rope order, for `rod`: the rod
  // the proxies were last rebuilt from, its state unchanged since. Evaluated once per rebuild (in one
  // sorted batch) and shared by everything that reads it in the substep: the leaves' sweep
  // (updateBoxes), the body contacts' reach and the rope-rope contacts' (contact/).
  const std::vector<double>& endSpeeds(const Rod& rod) const;
  // The rest arclength (m from the rod's start, as the contact rules measure it) at each capsule end,
  // size() + 1 increasing values, for `rod`: the rod the proxies were last rebuilt from. Computed
  // again only when its knots or its rest lengths (its integrals' revision) have changed.
  const std::vector<double>& endArcs(const Rod& rod) const;
  // The curve parameter of the point of capsule i's axis nearest to `point` (world frame).
  double parameterNear(int i, const btVector3& point) const;

  const btCollisionObject& object() const { return *object_; }
  btCollisionObject& object() { return *object_; }
  const RopeShape& shape() const { return *shape_; }
  // The midphase tree (leaves: swept capsule boxes; leaf->dataAsInt = capsule index): Bullet's queries
  // and the rope-body and rope-rope midphase walk it.
  const btDbvt& tree() const { return *shape_->getDynamicAabbTree(); }
  // The tree's leaf boxes (x, y, z as the leaves hold them) in capsule order, in one array: a short
  // rope's self-contact scan (rope_world.cpp, findSelfPairs) reads these rather than the nodes (see
  // leafBoxes_).
  const std::vector<btDbvtVolume>& leafBoxes() const { return leafBoxes_; }
  // Midphase: the capsules whose leaves meet the box [lo, hi] (world frame) grown by the part of the
  // speculative margin the leaves do not carry, in increasing order, into `out` (cleared first);
  // `stack` is the traversal's scratch.
  void capsulesOverlapping(const btVector3& lo, const btVector3& hi, std::vector<int>& out, btNodeStack& stack) const;

  // The rope a collision object is, or nullptr if it is not a dynamic rope's object.
  static RopeObject* ropeOf(const btCollisionObject& object);
  // Cache hints (rope/common/prefetch.h) for the capsules, the object and the shape (this object's
  // own bytes are the caller's to ask for first: RopeObject::prefetchParts).
  void prefetch() const;

 private:
  void configureObject(void* owner, int tag);
  void requireCapsule(int i) const;
  void addCapsule();
  void resize(int count);
  // updateBoxes without the broadphase: the capsules, their leaves and the object's box.
  int fitBoxes(const Rod& rod, double predictionTime, double margin);
  // The object's box from the tree's root (false, and the box kept, if too large), without Bullet.
  bool setObjectBox();

  int capsulesPerSpan_;
  btScalar radius_;
  std::vector<CapsuleProxy> proxies_;
  std::vector<btVector3> axis_;  // size() + 1 axis points at the last rebuild
  std::vector<double> ends_;     // scratch of rebuild: the capsule ends' curve parameters
  // The rod the capsules were last rebuilt from (degree -1: none, or caller-built capsules): its
  // knots, control points and velocities, so that a rebuild from the same rod state keeps them.
  int rebuiltDegree_ = -1;
  std::vector<double> rebuiltKnots_;
  PointList rebuiltPoints_, rebuiltVelocities_;
  mutable std::vector<double> speeds_;  // endSpeeds: |C'(s)| at each capsule end, m/s
  mutable bool speedsCurrent_ = false;  // speeds_ belong to the last rebuild
  mutable PointList velocities_;        // scratch of endSpeeds
  mutable std::vector<double> arcs_;    // endArcs: rest arclength at each capsule end, m
  mutable bool arcsCurrent_ = false;    // arcs_ belong to the knots of the last rebuild ...
  mutable std::uint64_t arcsRevision_ = 0;  // ... and to the rod's integrals of this revision
  mutable std::vector<double> restStarts_;  // scratch of endArcs: rest arclength at each span start
  std::vector<double> middles_;  // scratch of updateBoxes: each capsule's middle parameter
  PointList points_;             // scratch: curve points or velocities at ends_ or middles_
  std::vector<std::unique_ptr<RopeCapsuleShape>> capsuleShapes_;
  std::unique_ptr<RopeShape> shape_;
  std::unique_ptr<btCollisionObject> object_;
  btCollisionWorld* world_ = nullptr;
  bool boxUnannounced_ = false;  // updateBoxesDeferred set a box the broadphase has not seen yet
  // Each capsule's tree leaf box as the tree holds it (x, y, z), in capsule order: fitLeaf and
  // capsulesOverlapping read these instead of the tree's nodes, which Bullet allocates one by one
  // all over the heap (with a thousand ropes, a cache miss per node every substep).
  std::vector<btDbvtVolume> leafBoxes_;
  // m: added to the object's broadphase box and to every capsulesOverlapping query, the part of the
  // speculative margin the leaves do not carry (capsule_proxies.cpp, kRopeReachShare); 0 for proxies
  // whose leaves the caller fits (kinematic ropes).
  btScalar queryPad_ = 0;
};

}  // namespace rope::bullet
