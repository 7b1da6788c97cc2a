// SPDX-License-Identifier: MIT
#include "bullet_bridge/capsule_proxies.h"

#include <LinearMath/btQuaternion.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "bullet_bridge/detail/bullet_math.h"
#include "bullet_bridge/detail/rest_arc.h"
#include "bullet_bridge/detail/tree_pairs.h"
#include "rope/common/error.h"
#include "rope/common/prefetch.h"

namespace rope::bullet {

namespace {

// Bullet's btCollisionWorld::updateSingleAabb disables objects whose box diagonal^2 reaches 1e12.
constexpr double kBulletAabbLimit2 = 1e12;
// A leaf is refitted only when the new swept box leaves it or it is more than twice this much larger
// than the new box on some side; it is then stored this much fatter (fraction of the radius). A rope
// at rest (or moving steadily) leaves its tree alone, and a leaf never stays much larger than needed.
constexpr double kLeafSlack = 0.1;
// A dynamic rope's leaves are padded by (1 + kRopeReachShare) radii (plus the motion, the bulge and
// the slack): two ropes' leaves then meet wherever their capsules are within the rope-rope reach
// (RopeRopeContacts::reach: at most half the two radii beyond them, plus the motion), and a
// body's query, grown by queryPad_ = max(0, margin - kRopeReachShare r), meets every capsule within
// the speculative margin, as when the leaves were padded by the margin itself (1 cm against a 5 mm
// rope: 7.75 mm of padding instead of 15, so a knot's or a heap's tree-against-tree search reports
// fewer distant pairs). A little over the half, for the rounding of the exact test's slack.
constexpr double kRopeReachShare = 0.55;
// Up to this many capsules a body query (capsulesOverlapping) scans the leaf boxes in order instead
// of walking the tree: a body's box usually covers much of a short rope, and the scan reads one
// array where the walk follows pointers to up to twice as many nodes scattered over the heap.
constexpr int kLinearQueryCapsules = 64;

double diagonal2(const btVector3& lo, const btVector3& hi) {
  const btVector3 d = hi - lo;
  return static_cast<double>(d.x()) * d.x() + static_cast<double>(d.y()) * d.y() + static_cast<double>(d.z()) * d.z();
}

// A kinematic rope's object: no Bullet pair except with a dynamic rope's object, which the dynamic
// rope's RopeWorld takes (rope_dispatch.h). Bullet's dispatcher asks checkCollideWith before it makes
// an algorithm; its queries (rayTest, contactTest, convexSweepTest) do not ask, so they still see it.
class PairsWithRopesOnly : public btCollisionObject {
 public:
  PairsWithRopesOnly() { m_checkCollideWith = 1; }
  bool checkCollideWithOverride(const btCollisionObject* other) const override {
    return other != nullptr && CapsuleProxies::ropeOf(*other) != nullptr;
  }
};

}  // namespace

void capsuleEnds(const KnotVector& knots, double begin, double end, int pieces, std::vector<double>& ends) {
  ends.clear();
  ends.push_back(begin);
  double previous = begin;
  for (int i = 0; i < knots.size(); ++i) {
    const double knot = knots[i];
    if (!(knot > previous) || knot > end) continue;
    for (int j = 1; j <= pieces; ++j) ends.push_back(j == pieces ? knot : previous + (knot - previous) * j / pieces);
    previous = knot;
  }
}

CapsuleProxies::CapsuleProxies(RopeObject& owner, int capsulesPerSpan, double radius)
    : capsulesPerSpan_(capsulesPerSpan),
      radius_(static_cast<btScalar>(radius)),
      shape_(std::make_unique<RopeShape>()),
      object_(std::make_unique<btCollisionObject>()) {
  configureObject(&owner, kRopeCapsuleTag);
}

CapsuleProxies::CapsuleProxies(void* owner, int tag, double radius)
    : capsulesPerSpan_(1),
      radius_(static_cast<btScalar>(radius)),
      shape_(std::make_unique<RopeShape>()),
      object_(std::make_unique<PairsWithRopesOnly>()) {
  configureObject(owner, tag);
}

void CapsuleProxies::configureObject(void* owner, int tag) {
  object_->setCollisionShape(shape_.get());
  object_->getWorldTransform().setIdentity();
  // Drawn by the RopeWorld's debug drawer (rope_debug_draw.h) or by the kinematic rope's action, not
  // a second time by Bullet's.
  object_->setCollisionFlags(object_->getCollisionFlags() | btCollisionObject::CF_STATIC_OBJECT |
                             btCollisionObject::CF_NO_CONTACT_RESPONSE |
                             btCollisionObject::CF_DISABLE_VISUALIZE_OBJECT);
  object_->setUserPointer(owner);
  object_->setUserIndex2(tag);
  // Always active, so Bullet's dispatcher hands every broadphase pair of a dynamic rope (against
  // sleeping and static bodies too) to the rope's collision algorithm (rope_dispatch.h), and those of
  // a kinematic rope with (always active) dynamic ropes to their RopeWorld.
  object_->setActivationState(DISABLE_DEACTIVATION);
}

CapsuleProxies::~CapsuleProxies() { removeFromWorld(); }

void CapsuleProxies::addToWorld(btCollisionWorld& world, int group, int mask) {
  world_ = &world;
  world.addCollisionObject(object_.get(), group, mask);
}

void CapsuleProxies::removeFromWorld() {
  if (world_ == nullptr) return;
  if (!orphaned()) world_->removeCollisionObject(object_.get());
  world_ = nullptr;
}

bool CapsuleProxies::orphaned() const { return world_ != nullptr && object_->getBroadphaseHandle() == nullptr; }

void CapsuleProxies::setFilter(int group, int mask) {
  if (world_ == nullptr || orphaned()) return;
  // Out and in again: Bullet keeps the pairs a proxy already has when its filter bits change.
  world_->removeCollisionObject(object_.get());
  world_->addCollisionObject(object_.get(), group, mask);
}

void CapsuleProxies::addCapsule() {
  capsuleShapes_.push_back(std::make_unique<RopeCapsuleShape>(radius_, static_cast<int>(capsuleShapes_.size())));
  btTransform identity;
  identity.setIdentity();
  shape_->addChildShape(identity, capsuleShapes_.back().get());
}

void CapsuleProxies::requireCapsule(int i) const {
  if (i < 0 || i >= size()) throw InvalidArgument("i", std::to_string(i), "must be in [0, " + std::to_string(size()) + ")");
}

void CapsuleProxies::placeCapsule(int i) {
  requireCapsule(i);
  const btVector3& a = axis_[static_cast<std::size_t>(i)];
  const btVector3& b = axis_[static_cast<std::size_t>(i) + 1];
  const btVector3 chord = b - a;
  const btScalar length = chord.length();
  btQuaternion rotation = btQuaternion::getIdentity();
  // The capsule's local Y axis onto the chord (Bullet picks a perpendicular axis for a reversed one).
  if (length > btScalar(0)) rotation = shortestArcQuat(btVector3(0, 1, 0), chord / length);
  shape_->getChildTransform(i) = btTransform(rotation, (a + b) * btScalar(0.5));
  capsuleShapes_[static_cast<std::size_t>(i)]->setHalfHeight(btScalar(0.5) * length);
}

void CapsuleProxies::rebuild(const Rod& rod) {
  const bool sameKnots = rod.degree() == rebuiltDegree_ && rod.knots().values() == rebuiltKnots_;
  // The ends' rest arclengths (endArcs) follow the knots and the rest lengths; a winch changes the
  // latter without moving a knot, which endArcs sees in the rod's integrals' revision.
  if (!sameKnots) arcsCurrent_ = false;
  // A rope rebuilds at the end of a substep (updateBoxes) and again at the start of the next, mostly
  // from the same curve: then the capsules stand (and so do the end speeds if the velocities do too).
  // Compared value by value, so any change of the rod in between (a winch, the user) rebuilds.
  if (sameKnots && rod.controlPoints() == rebuiltPoints_) {
    if (!(rod.velocities() == rebuiltVelocities_)) {
      speedsCurrent_ = false;
      rebuiltVelocities_ = rod.velocities();
    }
    return;
  }
  capsuleEnds(rod.knots(), rod.beginParameter(), rod.endParameter(), capsulesPerSpan_, ends_);  // no allocation in a steady state
  rod.positionsAt(ends_, points_);  // sorted: no span search
  speedsCurrent_ = false;
  axis_.resize(ends_.size());
  for (std::size_t i = 0; i < ends_.size(); ++i) axis_[i] = toBullet(points_[i]);
  resize(static_cast<int>(ends_.size()) - 1);
  rebuiltDegree_ = rod.degree();
  rebuiltKnots_ = rod.knots().values();
  rebuiltPoints_ = rod.controlPoints();
  rebuiltVelocities_ = rod.velocities();
}

void CapsuleProxies::rebuild(const std::vector<double>& ends, const std::vector<btVector3>& axis) {
  if (ends.size() < 2) throw InvalidArgument("ends", std::to_string(ends.size()) + " ends", "need at least 2 (one capsule)");
  if (axis.size() != ends.size()) {
    throw InvalidArgument("axis", std::to_string(axis.size()) + " points", "must have one point per end (" + std::to_string(ends.size()) + ")");
  }
  ends_ = ends;
  axis_ = axis;
  speedsCurrent_ = false;
  arcsCurrent_ = false;
  rebuiltDegree_ = -1;  // the capsules no longer come from a rod
  resize(static_cast<int>(ends_.size()) - 1);
}

void CapsuleProxies::resize(int count) {
  // Children leave and join at the end only, so child index = capsule index stays true.
  while (size() > count) {
    shape_->removeChildShapeByIndex(size() - 1);
    capsuleShapes_.pop_back();
    proxies_.pop_back();
    leafBoxes_.pop_back();
  }
  while (size() < count) {
    CapsuleProxy proxy;
    proxy.object = object_.get();
    proxies_.push_back(proxy);
    addCapsule();
    placeCapsule(size() - 1);
    // Its first leaf: the capsule's own box, so a capsule created mid-run is found before its first
    // updateBoxes.
    btVector3 lo, hi;
    capsuleShapes_.back()->getAabb(shape_->getChildTransform(size() - 1), lo, hi);
    btDbvtVolume box = btDbvtVolume::FromMM(lo, hi);
    shape_->getDynamicAabbTree()->update(shape_->getChildList()[size() - 1].m_node, box);
    leafBoxes_.push_back(box);
  }
  for (int i = 0; i < count; ++i) {
    proxies_[static_cast<std::size_t>(i)].s0 = ends_[static_cast<std::size_t>(i)];
    proxies_[static_cast<std::size_t>(i)].s1 = ends_[static_cast<std::size_t>(i) + 1];
  }
}

int CapsuleProxies::updateBoxes(const Rod& rod, double predictionTime, double margin) {
  const int overflows = fitBoxes(rod, predictionTime, margin);
  announceObjectBox();  // nothing if the object's box was kept (too large) or there is no tree
  return overflows;
}

int CapsuleProxies::updateBoxesDeferred(const Rod& rod, double predictionTime, double margin) {
  return fitBoxes(rod, predictionTime, margin);
}

void CapsuleProxies::announceObjectBox() {
  if (!boxUnannounced_) return;
  boxUnannounced_ = false;
  if (world_ != nullptr && !orphaned()) world_->updateSingleAabb(object_.get());
}

int CapsuleProxies::fitBoxes(const Rod& rod, double predictionTime, double margin) {
  rebuild(rod);
  // The leaves carry the rope-rope share of the reach; what the speculative margin asks beyond it, the
  // body queries and the broadphase box add (queryPad_).
  queryPad_ = static_cast<btScalar>(std::max(0.0, margin - kRopeReachShare * static_cast<double>(radius_)));
  int overflows = 0;
  endSpeeds(rod);  // each end is shared by two capsules: its speed once
  middles_.resize(static_cast<std::size_t>(size()));
  for (int i = 0; i < size(); ++i) {
    const CapsuleProxy& proxy = proxies_[static_cast<std::size_t>(i)];
    middles_[static_cast<std::size_t>(i)] = 0.5 * (proxy.s0 + proxy.s1);
  }
  rod.positionsAt(middles_, points_);
  for (int i = 0; i < size(); ++i) {
    // The compound's children follow here, not in every rebuild: only Bullet's queries read them,
    // between steps (4 % of a 1000-rope step when placed twice per substep).
    placeCapsule(i);
    const btVector3& a = axis_[static_cast<std::size_t>(i)];
    const btVector3& b = axis_[static_cast<std::size_t>(i) + 1];
    // How far the curve bulges out of the chord: its middle point's (points_) distance from the chord's midpoint.
    const btScalar bulge = (toBullet(points_[static_cast<std::size_t>(i)]) - (a + b) * btScalar(0.5)).length();
    // How far the capsule can move in the step, in any direction (the body and rope-rope midphase
    // test the chord's box grown by it: body_contacts.cpp, rope_rope_contact.cpp).
    const double reach = predictionTime * std::max(speeds_[static_cast<std::size_t>(i)], speeds_[static_cast<std::size_t>(i) + 1]);
    const btScalar pad = radius_ * btScalar(1.0 + kRopeReachShare) + static_cast<btScalar>(reach) + bulge;
    btVector3 lo = a, hi = a;
    lo.setMin(b);
    hi.setMax(b);
    lo -= btVector3(pad, pad, pad);
    hi += btVector3(pad, pad, pad);
    if (!fitLeaf(i, lo, hi)) ++overflows;
  }
  if (shape_->getDynamicAabbTree()->m_root == nullptr) return overflows;
  return setObjectBox() ? overflows : size();
}

const std::vector<double>& CapsuleProxies::endSpeeds(const Rod& rod) const {
  if (speedsCurrent_) return speeds_;
  rod.velocitiesAt(ends_, velocities_);  // sorted: no span search
  speeds_.resize(ends_.size());
  for (std::size_t i = 0; i < ends_.size(); ++i) speeds_[i] = velocities_[i].norm();
  speedsCurrent_ = true;
  return speeds_;
}

const std::vector<double>& CapsuleProxies::endArcs(const Rod& rod) const {
  if (arcsCurrent_ && arcsRevision_ == rod.integrals().revision()) return arcs_;
  buildRestArc(rod, restStarts_);
  arcs_.resize(ends_.size());
  for (std::size_t i = 0; i < ends_.size(); ++i) arcs_[i] = restArcAt(rod, restStarts_, ends_[i]);
  arcsCurrent_ = true;
  arcsRevision_ = rod.integrals().revision();
  return arcs_;
}

bool CapsuleProxies::fitLeaf(int i, const btVector3& lo, const btVector3& hi) {
  requireCapsule(i);
  const double d2 = diagonal2(lo, hi);
  // Keep the previous leaf: Bullet would take such an object out of the simulation.
  if (!std::isfinite(d2) || d2 >= kBulletAabbLimit2) return false;
  const btScalar slack = static_cast<btScalar>(kLeafSlack) * radius_;
  const btVector3 slack3(slack, slack, slack);
  btDbvtVolume& leafBox = leafBoxes_[static_cast<std::size_t>(i)];
  const btDbvtVolume box = btDbvtVolume::FromMM(lo, hi);
  const btDbvtVolume loose = btDbvtVolume::FromMM(lo - slack3 * 2, hi + slack3 * 2);
  if (!leafBox.Contain(box) || !loose.Contain(leafBox)) {
    btDbvtVolume fat = btDbvtVolume::FromMM(lo - slack3, hi + slack3);
    shape_->getDynamicAabbTree()->update(shape_->getChildList()[i].m_node, fat);
    leafBox = fat;
  }
  return true;
}

bool CapsuleProxies::fitObjectBox() {
  if (!setObjectBox()) return false;
  announceObjectBox();
  return true;
}

bool CapsuleProxies::setObjectBox() {
  const btDbvt& tree = *shape_->getDynamicAabbTree();
  if (tree.m_root == nullptr) return true;
  const btVector3 pad(queryPad_, queryPad_, queryPad_);
  const btVector3 lo = tree.m_root->volume.Mins() - pad, hi = tree.m_root->volume.Maxs() + pad;
  const double d2 = diagonal2(lo, hi);
  if (!std::isfinite(d2) || d2 >= kBulletAabbLimit2) return false;  // the rope's box keeps its last value
  shape_->setBox(lo, hi);
  boxUnannounced_ = true;
  return true;
}

void CapsuleProxies::capsulesOverlapping(const btVector3& lo, const btVector3& hi, std::vector<int>& out,
                                         btNodeStack& stack) const {
  // The walk of btDbvt::collideTVNoStackAlloc (the same leaves), with the branch-free box test and
  // without a virtual call per leaf: every body near a rope asks this every substep.
  out.clear();
  const btVector3 pad(queryPad_, queryPad_, queryPad_);
  const btDbvtVolume box = btDbvtVolume::FromMM(lo - pad, hi + pad);
  if (size() <= kLinearQueryCapsules) {
    // The same capsules as the walk below: a node's box contains its leaves' (btDbvt merges them
    // exactly), so a leaf that meets the box has no ancestor that misses it. Already in order.
    for (int i = 0; i < size(); ++i)
      if (boxesMeet(leafBoxes_[static_cast<std::size_t>(i)], box)) out.push_back(i);
    return;
  }
  const btDbvtNode* root = shape_->getDynamicAabbTree()->m_root;
  if (root == nullptr || !boxesMeet(root->volume, box)) return;
  stack.resize(0);
  stack.push_back(root);
  while (stack.size() > 0) {
    const btDbvtNode* node = stack[stack.size() - 1];
    stack.pop_back();
    if (node->isleaf()) {
      out.push_back(node->dataAsInt);
      continue;
    }
    for (const btDbvtNode* child : node->childs)
      if (boxesMeet(child->volume, box)) stack.push_back(child);
  }
  std::sort(out.begin(), out.end());
}

Capsule CapsuleProxies::capsule(int i) const {
  Capsule capsule;
  capsule.a = axis_[static_cast<std::size_t>(i)];
  capsule.b = axis_[static_cast<std::size_t>(i) + 1];
  capsule.radius = radius_;
  return capsule;
}

double CapsuleProxies::parameterNear(int i, const btVector3& point) const {
  const Capsule c = capsule(i);
  const btVector3 axis = c.b - c.a;
  const double axis2 = static_cast<double>(axis.length2());
  double t = axis2 > 0.0 ? static_cast<double>((point - c.a).dot(axis)) / axis2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const CapsuleProxy& p = proxy(i);
  return p.s0 + t * (p.s1 - p.s0);
}

void CapsuleProxies::prefetch() const {
  prefetchVector(proxies_);
  prefetchVector(leafBoxes_);
  prefetchVector(rebuiltKnots_);
  prefetchVector(rebuiltPoints_);
  prefetchVector(rebuiltVelocities_);
  prefetchVector(axis_);
  prefetchVector(ends_);
  prefetchVector(speeds_);
  prefetchBytes(object_.get(), sizeof(btCollisionObject));
  prefetchBytes(shape_.get(), sizeof(RopeShape));
}

RopeObject* CapsuleProxies::ropeOf(const btCollisionObject& object) {
  if (object.getUserIndex2() != kRopeCapsuleTag) return nullptr;
  return static_cast<RopeObject*>(object.getUserPointer());
}

}  // namespace rope::bullet
