// SPDX-License-Identifier: MIT
#include "bullet_bridge/rope_queries.h"

#include <BulletCollision/BroadphaseCollision/btBroadphaseInterface.h>
#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>
#include <BulletCollision/CollisionShapes/btCollisionShape.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "bullet_bridge/find_contacts.h"
#include "bullet_bridge/kinematic_rope.h"
#include "bullet_bridge/narrowphase/ray_capsule.h"
#include "bullet_bridge/rope_world.h"
#include "rope/common/error.h"

namespace rope::bullet {

namespace {

void requireFinitePoint(const std::string& name, const btVector3& p) {
  static const char* const kAxes[3] = {".x", ".y", ".z"};
  for (int i = 0; i < 3; ++i) requireFinite(name + kAxes[i], static_cast<double>(p[i]));
}

// The capsules of a rope whose tree leaves a ray crosses (btDbvt::rayTest), then the exact capsule.
class RopeRayCallback : public btBroadphaseRayCallback {
 public:
  RopeRayCallback(const RopeWorld& world, const btVector3& from, const btVector3& to)
      : world_(world), from_(from), to_(to) {
    const btVector3 direction = to - from;
    const btScalar length = direction.length();
    const btVector3 unit = length > btScalar(0) ? direction / length : btVector3(1, 0, 0);
    for (int i = 0; i < 3; ++i) {
      m_rayDirectionInverse[i] = unit[i] == btScalar(0) ? btScalar(BT_LARGE_FLOAT) : btScalar(1) / unit[i];
      m_signs[i] = m_rayDirectionInverse[i] < btScalar(0);
    }
    m_lambda_max = length;
  }

  bool process(const btBroadphaseProxy* proxy) override {
    const auto* object = static_cast<const btCollisionObject*>(proxy->m_clientObject);
    RayHit hit;
    const CapsuleProxies* proxies = nullptr;
    if (const KinematicRope* kinematic = KinematicRope::ropeOf(*object)) {
      hit.kinematicRope = kinematic;
      proxies = &kinematic->proxies();
    } else if (const RopeObject* rope = CapsuleProxies::ropeOf(*object); rope != nullptr && world_.contains(*rope)) {
      hit.rope = rope;
      proxies = &rope->proxies();
    }
    if (proxies == nullptr || proxies->size() == 0) return true;
    struct Leaves : btDbvt::ICollide {
      void Process(const btDbvtNode* leaf) override { capsules.push_back(leaf->dataAsInt); }
      std::vector<int> capsules;
    } leaves;
    btDbvt::rayTest(proxies->tree().m_root, from_, to_, leaves);
    for (const int index : leaves.capsules) {
      const CapsuleProxy& capsuleProxy = proxies->proxy(index);
      consider(proxies->capsule(index), capsuleProxy.s0, capsuleProxy.s1, hit);
    }
    return true;
  }

  std::optional<RayHit> best;

 private:

  // The exact hit of the ray on a capsule whose axis runs from C(s0) to C(s1), kept if nearest so far;
  // hit names the rope.
  void consider(const Capsule& capsule, double s0, double s1, RayHit hit) {
    double lambda = 0.0, t = 0.0;
    if (!rayCapsule(from_, to_ - from_, capsule, lambda, t)) return;
    if (best && !(lambda < best->fraction)) return;
    hit.fraction = lambda;
    hit.s = s0 + t * (s1 - s0);
    hit.point = from_ + (to_ - from_) * static_cast<btScalar>(lambda);
    const btVector3 outward = hit.point - capsule.axisPoint(static_cast<btScalar>(t));
    hit.normal = outward.length() > btScalar(0) ? outward.normalized() : btVector3(0, 0, 1);
    best = hit;
  }

  const RopeWorld& world_;
  btVector3 from_, to_;
};

class RopeAabbCallback : public btBroadphaseAabbCallback {
 public:
  explicit RopeAabbCallback(const RopeWorld& world) : world_(world) {}
  bool process(const btBroadphaseProxy* proxy) override {
    const auto* object = static_cast<const btCollisionObject*>(proxy->m_clientObject);
    const RopeObject* rope = CapsuleProxies::ropeOf(*object);
    if (rope != nullptr && world_.contains(*rope)) ropes.push_back(rope);
    if (const KinematicRope* kinematic = KinematicRope::ropeOf(*object)) kinematicRopes.push_back(kinematic);
    return true;
  }
  std::vector<const RopeObject*> ropes;
  std::vector<const KinematicRope*> kinematicRopes;

 private:
  const RopeWorld& world_;
};

}  // namespace

std::optional<RayHit> rayTestRopes(const RopeWorld& world, const btVector3& from, const btVector3& to) {
  requireFinitePoint("from", from);
  requireFinitePoint("to", to);
  RopeRayCallback callback(world, from, to);
  const_cast<RopeWorld&>(world).dynamicsWorld().getBroadphase()->rayTest(from, to, callback);
  return callback.best;
}

std::optional<RayHit> rayTest(const RopeWorld& world, const btVector3& from, const btVector3& to) {
  std::optional<RayHit> best = rayTestRopes(world, from, to);
  // Bullet's own ray test sees the ropes' objects too (at its convex cast's precision): bodies only.
  struct BodiesOnly : btCollisionWorld::ClosestRayResultCallback {
    using ClosestRayResultCallback::ClosestRayResultCallback;
    bool needsCollision(btBroadphaseProxy* proxy) const override {
      const auto* object = static_cast<const btCollisionObject*>(proxy->m_clientObject);
      return CapsuleProxies::ropeOf(*object) == nullptr && KinematicRope::ropeOf(*object) == nullptr &&
             ClosestRayResultCallback::needsCollision(proxy);
    }
  } bodies(from, to);
  world.dynamicsWorld().rayTest(from, to, bodies);
  if (bodies.hasHit() && (!best || bodies.m_closestHitFraction < best->fraction)) {
    RayHit hit;
    hit.body = bodies.m_collisionObject;
    hit.fraction = static_cast<double>(bodies.m_closestHitFraction);
    hit.point = bodies.m_hitPointWorld;
    hit.normal = bodies.m_hitNormalWorld;
    best = hit;
  }
  return best;
}

std::vector<RopeContactHit> contactTest(const RopeWorld& world, const btCollisionObject& object, double margin) {
  requireNonNegative("margin", margin);
  const btCollisionShape* shape = object.getCollisionShape();
  if (shape == nullptr) throw InvalidArgument("object.shape", "null", "the collision object has no shape");
  const btTransform& transform = object.getWorldTransform();
  for (int row = 0; row < 3; ++row) {
    requireFinitePoint("object.transform.basis[" + std::to_string(row) + "]", transform.getBasis()[row]);
  }
  requireFinitePoint("object.transform.origin", transform.getOrigin());
  btVector3 lo, hi;
  shape->getAabb(transform, lo, hi);
  const btScalar grow = static_cast<btScalar>(margin);
  lo -= btVector3(grow, grow, grow);
  hi += btVector3(grow, grow, grow);
  RopeAabbCallback callback(world);
  const_cast<RopeWorld&>(world).dynamicsWorld().getBroadphase()->aabbTest(lo, hi, callback);
  // Deterministic order: by rope (world order), then capsule index.
  std::vector<std::pair<int, const RopeObject*>> ropes;
  for (const RopeObject* rope : callback.ropes) {
    const int ropeIndex =
        static_cast<int>(std::find(world.ropes().begin(), world.ropes().end(), rope) - world.ropes().begin());
    ropes.push_back({ropeIndex, rope});
  }
  std::sort(ropes.begin(), ropes.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<RopeContactHit> hits;
  std::vector<Contact> contacts;
  std::vector<int> capsules;
  btNodeStack stack;
  for (const auto& entry : ropes) {
    const RopeObject* rope = entry.second;
    rope->proxies().capsulesOverlapping(lo, hi, capsules, stack);
    for (const int index : capsules) {
      contacts.clear();
      findContacts(rope->proxies().capsule(index), object, margin, contacts);
      const CapsuleProxy& proxy = rope->proxies().proxy(index);
      for (const Contact& contact : contacts) {
        RopeContactHit hit;
        hit.rope = rope;
        hit.s = proxy.s0 + static_cast<double>(contact.t) * (proxy.s1 - proxy.s0);
        hit.contact = contact;
        hits.push_back(hit);
      }
    }
  }
  // Kinematic ropes, in the world's object order, then capsule index.
  std::sort(callback.kinematicRopes.begin(), callback.kinematicRopes.end(),
            [](const KinematicRope* a, const KinematicRope* b) {
              return a->collisionObject().getWorldArrayIndex() < b->collisionObject().getWorldArrayIndex();
            });
  for (const KinematicRope* rope : callback.kinematicRopes) {
    if (&rope->collisionObject() == &object) continue;
    rope->proxies().capsulesOverlapping(lo, hi, capsules, stack);
    for (const int index : capsules) {
      contacts.clear();
      findContacts(rope->capsule(index), object, margin, contacts);
      const auto [s0, s1] = rope->capsuleParameters(index);
      for (const Contact& contact : contacts) {
        RopeContactHit hit;
        hit.kinematicRope = rope;
        hit.s = s0 + static_cast<double>(contact.t) * (s1 - s0);
        hit.contact = contact;
        hits.push_back(hit);
      }
    }
  }
  return hits;
}

}  // namespace rope::bullet

namespace rope::bullet {

namespace {

// The capsule chain of a rope's or a kinematic rope's object, with the location naming the rope.
const CapsuleProxies* chainOf(const btCollisionObject& object, RopeHitLocation& location) {
  if (const RopeObject* rope = CapsuleProxies::ropeOf(object)) {
    location.rope = rope;
    return &rope->proxies();
  }
  if (const KinematicRope* rope = KinematicRope::ropeOf(object)) {
    location.kinematicRope = rope;
    return &rope->proxies();
  }
  return nullptr;
}

}  // namespace

std::optional<RopeHitLocation> ropeHit(const btCollisionObject& object, int childIndex, const btVector3& point) {
  RopeHitLocation location;
  const CapsuleProxies* proxies = chainOf(object, location);
  if (proxies == nullptr) return std::nullopt;
  requireFinitePoint("point", point);
  if (childIndex < 0 || childIndex >= proxies->size()) {
    throw InvalidArgument("childIndex", std::to_string(childIndex),
                          "must name one of the rope's " + std::to_string(proxies->size()) + " capsules");
  }
  location.capsule = childIndex;
  location.s = proxies->parameterNear(childIndex, point);
  return location;
}

std::optional<RopeHitLocation> ropeHit(const btCollisionObject& object, const btVector3& point) {
  RopeHitLocation location;
  const CapsuleProxies* found = chainOf(object, location);
  if (found == nullptr) return std::nullopt;
  requireFinitePoint("point", point);
  const CapsuleProxies& proxies = *found;
  if (proxies.size() == 0) return std::nullopt;
  // The capsule whose surface is nearest to the point (a point on the rope lies in its capsule's
  // leaf; the tree narrows the search to the leaves around it, all capsules if none).
  std::vector<int> capsules;
  btNodeStack stack;
  proxies.capsulesOverlapping(point, point, capsules, stack);
  if (capsules.empty()) {
    for (int i = 0; i < proxies.size(); ++i) capsules.push_back(i);
  }
  int best = capsules.front();
  double bestGap = std::numeric_limits<double>::infinity();
  for (const int i : capsules) {
    const Capsule capsule = proxies.capsule(i);
    const double s = proxies.parameterNear(i, point);
    const CapsuleProxy& proxy = proxies.proxy(i);
    const double t = proxy.s1 > proxy.s0 ? (s - proxy.s0) / (proxy.s1 - proxy.s0) : 0.0;
    const double gap = std::abs(static_cast<double>((point - capsule.axisPoint(static_cast<btScalar>(t))).length()) -
                                static_cast<double>(capsule.radius));
    if (gap < bestGap) {
      bestGap = gap;
      best = i;
    }
  }
  location.capsule = best;
  location.s = proxies.parameterNear(best, point);
  return location;
}

}  // namespace rope::bullet
