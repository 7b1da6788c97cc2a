// SPDX-License-Identifier: MIT
#include "bullet_bridge/capsule_proxies.h"

#include <algorithm>
#include <cmath>

#include "bullet_bridge/bullet_math.h"

namespace rope::bullet {

namespace {

// Bullet's btCollisionWorld::updateSingleAabb disables objects whose box diagonal^2 reaches 1e12.
constexpr double kBulletAabbLimit2 = 1e12;

}  // namespace

CapsuleProxies::CapsuleProxies(RopeObject& owner, int capsulesPerSpan, double radius)
    : owner_(owner), capsulesPerSpan_(capsulesPerSpan), radius_(static_cast<btScalar>(radius)) {}

CapsuleProxies::~CapsuleProxies() { removeFromWorld(); }

void CapsuleProxies::addToWorld(btCollisionWorld& world, int group, int mask) {
  world_ = &world;
  group_ = group;
  mask_ = mask;
  for (CapsuleProxy& proxy : proxies_) world.addCollisionObject(proxy.object.get(), group, mask);
}

void CapsuleProxies::removeFromWorld() {
  if (world_ == nullptr) return;
  if (!orphaned()) {
    for (CapsuleProxy& proxy : proxies_) world_->removeCollisionObject(proxy.object.get());
  }
  world_ = nullptr;
}

bool CapsuleProxies::orphaned() const {
  if (world_ == nullptr || proxies_.empty()) return false;
  for (const CapsuleProxy& proxy : proxies_) {
    if (proxy.object->getBroadphaseHandle() != nullptr) return false;
  }
  return true;
}

void CapsuleProxies::rebuild(const Rod& rod) {
  // Parameters of the capsule ends: every non-empty span cut into capsulesPerSpan equal pieces.
  const KnotVector& knots = rod.knots();
  const double begin = rod.beginParameter();
  const double end = rod.endParameter();
  std::vector<double> ends;
  ends.push_back(begin);
  double previous = begin;
  for (int i = 0; i < knots.size(); ++i) {
    const double knot = knots[i];
    if (!(knot > previous) || knot > end) continue;
    for (int j = 1; j <= capsulesPerSpan_; ++j) {
      ends.push_back(j == capsulesPerSpan_ ? knot : previous + (knot - previous) * j / capsulesPerSpan_);
    }
    previous = knot;
  }
  const int count = static_cast<int>(ends.size()) - 1;

  while (size() > count) {
    if (world_ != nullptr) world_->removeCollisionObject(proxies_.back().object.get());
    proxies_.pop_back();
  }
  axis_.resize(ends.size());
  for (std::size_t i = 0; i < ends.size(); ++i) axis_[i] = toBullet(rod.position(ends[i]));
  while (size() < count) {
    CapsuleProxy proxy;
    proxy.shape = std::make_unique<SweptBoxShape>();
    proxy.object = std::make_unique<btCollisionObject>();
    proxy.object->setCollisionShape(proxy.shape.get());
    proxy.object->setCollisionFlags(proxy.object->getCollisionFlags() | btCollisionObject::CF_STATIC_OBJECT |
                                    btCollisionObject::CF_NO_CONTACT_RESPONSE);
    proxy.object->setUserPointer(&owner_);
    proxy.object->setUserIndex(size());
    proxy.object->setUserIndex2(kRopeCapsuleTag);
    // Never "active" for Bullet (a static object asleep: no island ever wakes it, since it has no
    // manifolds), so its dispatcher skips pairs of two rope capsules at once
    // (btCollisionDispatcher::needsCollision); the bridge reads them from the pair cache itself.
    // DISABLE_SIMULATION would say the same, but Bullet uses it to report an object it gave up on.
    proxy.object->setActivationState(ISLAND_SLEEPING);
    // A box covering the capsule now, so a capsule created mid-run is found before its first update.
    const std::size_t i = proxies_.size();
    btVector3 lo = axis_[i], hi = axis_[i];
    lo.setMin(axis_[i + 1]);
    hi.setMax(axis_[i + 1]);
    const btVector3 pad(radius_, radius_, radius_);
    proxy.shape->setHalfExtents((hi - lo) * btScalar(0.5) + pad);
    proxy.object->getWorldTransform().setIdentity();
    proxy.object->getWorldTransform().setOrigin((lo + hi) * btScalar(0.5));
    if (world_ != nullptr) world_->addCollisionObject(proxy.object.get(), group_, mask_);
    proxies_.push_back(std::move(proxy));
  }
  for (int i = 0; i < count; ++i) {
    proxies_[static_cast<std::size_t>(i)].s0 = ends[static_cast<std::size_t>(i)];
    proxies_[static_cast<std::size_t>(i)].s1 = ends[static_cast<std::size_t>(i) + 1];
  }
}

int CapsuleProxies::updateBoxes(const Rod& rod, double predictionTime, double margin) {
  rebuild(rod);
  int overflows = 0;
  std::vector<btVector3> predicted(axis_.size());
  for (int i = 0; i <= size(); ++i) {
    const double s = i < size() ? proxies_[static_cast<std::size_t>(i)].s0 : proxies_.back().s1;
    predicted[static_cast<std::size_t>(i)] = axis_[static_cast<std::size_t>(i)] +
                                             toBullet(rod.velocity(s) * predictionTime);
  }
  for (int i = 0; i < size(); ++i) {
    CapsuleProxy& proxy = proxies_[static_cast<std::size_t>(i)];
    const btVector3& a = axis_[static_cast<std::size_t>(i)];
    const btVector3& b = axis_[static_cast<std::size_t>(i) + 1];
    // How far the curve bulges out of the chord: its midpoint's distance from the chord's midpoint.
    const btScalar bulge = (toBullet(rod.position(0.5 * (proxy.s0 + proxy.s1))) - (a + b) * btScalar(0.5)).length();
    btVector3 lo = a, hi = a;
    const btVector3* const corners[3] = {&b, &predicted[static_cast<std::size_t>(i)],
                                         &predicted[static_cast<std::size_t>(i) + 1]};
    for (const btVector3* p : corners) {
      lo.setMin(*p);
      hi.setMax(*p);
    }
    const btScalar pad = radius_ + static_cast<btScalar>(margin) + bulge;
    lo -= btVector3(pad, pad, pad);
    hi += btVector3(pad, pad, pad);
    const btVector3 diagonal = hi - lo;
    const double diagonal2 = static_cast<double>(diagonal.x()) * diagonal.x() +
                             static_cast<double>(diagonal.y()) * diagonal.y() +
                             static_cast<double>(diagonal.z()) * diagonal.z();
    if (!std::isfinite(diagonal2) || diagonal2 >= kBulletAabbLimit2) {
      ++overflows;  // keep the previous box: Bullet would take this object out of the simulation
      continue;
    }
    proxy.shape->setHalfExtents(diagonal * btScalar(0.5));
    proxy.object->getWorldTransform().setOrigin((lo + hi) * btScalar(0.5));
    if (world_ != nullptr) world_->updateSingleAabb(proxy.object.get());
  }
  return overflows;
}

Capsule CapsuleProxies::capsule(int i) const {
  Capsule capsule;
  capsule.a = axis_[static_cast<std::size_t>(i)];
  capsule.b = axis_[static_cast<std::size_t>(i) + 1];
  capsule.radius = radius_;
  return capsule;
}

RopeObject* CapsuleProxies::ropeOf(const btCollisionObject& object) {
  if (object.getUserIndex2() != kRopeCapsuleTag) return nullptr;
  return static_cast<RopeObject*>(object.getUserPointer());
}

}  // namespace rope::bullet
