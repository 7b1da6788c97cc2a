// SPDX-License-Identifier: MIT
#include "bullet_bridge/kinematic_rope.h"

#include <BulletCollision/BroadphaseCollision/btBroadphaseInterface.h>
#include <LinearMath/btIDebugDraw.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "bullet_bridge/collision_object/capsule_dispatch.h"
#include "bullet_bridge/detail/body_state.h"
#include "bullet_bridge/find_contacts.h"
#include "bullet_bridge/detail/guarded_call.h"
#include "bullet_bridge/contact/kinematic_push.h"
#include "bullet_bridge/detail/world_membership.h"
#include "rope/common/error.h"
#include "rope/spline/bspline_curve.h"
#include "rope/tractrix/tractrix_segment.h"

namespace rope::bullet {

namespace {

btVector3 toBullet(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()), static_cast<btScalar>(v.z()));
}

Vec3 toVec(const btVector3& v) {
  return Vec3(static_cast<double>(v.x()), static_cast<double>(v.y()), static_cast<double>(v.z()));
}

// A finite position the tractrix accepts (no exception: used inside a substep).
bool acceptable(const Vec3& p) {
  for (int c = 0; c < 3; ++c) {
    if (!std::isfinite(p[c]) || std::fabs(p[c]) > kMaxTractrixCoordinate) return false;
  }
  return true;
}

bool finite(const btVector3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

bool finiteContact(const Contact& contact) {
  return finite(contact.pointOnBody) && finite(contact.normal) && std::isfinite(contact.distance) &&
         std::isfinite(contact.t);
}

void requireTarget(const char* name, const btVector3& p) {
  static const char* const kAxes[3] = {".x", ".y", ".z"};
  for (int c = 0; c < 3; ++c) requireTractrixCoordinate(std::string(name) + kAxes[c], static_cast<double>(p[c]));
}

// The world's dynamic body behind a broadphase proxy that this rope may push, else nullptr.
btRigidBody* pushableBody(const btBroadphaseProxy& proxy, int group, int mask, const btRigidBody* followed) {
  auto* object = static_cast<btCollisionObject*>(proxy.m_clientObject);
  if (object == nullptr) return nullptr;
  if (object->getUserIndex2() == kKinematicRopeTag || object->getUserIndex2() == kRopeCapsuleTag) return nullptr;
  if (!object->hasContactResponse()) return nullptr;
  if ((proxy.m_collisionFilterGroup & mask) == 0 || (group & proxy.m_collisionFilterMask) == 0) return nullptr;
  btRigidBody* body = btRigidBody::upcast(object);
  if (body == nullptr || body == followed || body->isStaticOrKinematicObject() || !(body->getInvMass() > 0)) {
    return nullptr;
  }
  return body;
}

}  // namespace

// Bullet calls updateAction once per internal substep, after that substep's integration.
class KinematicRope::Action : public btActionInterface {
 public:
  explicit Action(KinematicRope& owner) : owner_(owner) {}
  // Nothing may leave Bullet's step (kinematic_rope.h, "Failures").
  void updateAction(btCollisionWorld*, btScalar dt) override {
    guardedCall([&] { owner_.substep(static_cast<double>(dt)); },
                [&](const char* message) { owner_.recoverFromException(message); });
  }
  // Bullet calls this from debugDrawWorld() (wireframe or AABB mode): the rope's centre line.
  void debugDraw(btIDebugDraw* drawer) override {
    if (drawer == nullptr) return;
    const btVector3 colour(btScalar(0.9), btScalar(0.5), btScalar(0.1));
    for (std::size_t i = 0; i + 1 < owner_.axis_.size(); ++i) drawer->drawLine(owner_.axis_[i], owner_.axis_[i + 1], colour);
  }

 private:
  KinematicRope& owner_;
};


KinematicRope::KinematicRope(TractrixRope rope, const KinematicRopeSettings& settings)
    : rope_([&] {
        settings.validate();
        return std::move(rope);
      }()),
      settings_(settings),
      action_(std::make_unique<Action>(*this)),
      target_(rope_.leadingEnd()),
      previousKnots_(rope_.knots()),
      previousPoints_(rope_.controlPoints()),
      proxies_(this, kKinematicRopeTag, settings_.radius) {
  rebuildCapsules(false);
}

KinematicRope::~KinematicRope() { removeFromWorld(); }

void KinematicRope::addToWorld(btDiscreteDynamicsWorld& world) {
  if (world_ != nullptr) {
    throw InvalidArgument("world", world_ == &world ? "this world" : "another world",
                          "the rope is already in a world; removeFromWorld() first");
  }
  world_ = &world;
  time_ = 0.0;
  report_ = KinematicRopeStepReport{};
  capsuleDispatch_ = CapsuleDispatch::acquire(world);
  proxies_.addToWorld(world, settings_.collisionGroup, settings_.collisionMask);
  world.addAction(action_.get());
}

void KinematicRope::removeFromWorld() {
  if (world_ == nullptr) return;
  // If the object lost its broadphase handle, the Bullet world was destroyed already and must not be
  // touched (CapsuleProxies::removeFromWorld leaves it alone then).
  if (!proxies_.orphaned()) world_->removeAction(action_.get());
  if (proxies_.orphaned() && capsuleDispatch_) capsuleDispatch_->detach();
  capsuleDispatch_.reset();
  proxies_.removeFromWorld();
  world_ = nullptr;
  report_.contacts.clear();  // their body pointers may outlive nothing else
}

void KinematicRope::followBodyPoint(btRigidBody* body, const btVector3& localPoint) {
  if (body == nullptr) throw InvalidArgument("body", "nullptr", "must be a rigid body");
  static const char* const kAxes[3] = {"localPoint.x", "localPoint.y", "localPoint.z"};
  for (int c = 0; c < 3; ++c) requireFinite(kAxes[c], static_cast<double>(localPoint[c]));
  driver_ = Driver::kBody;
  body_ = body;
  bodyIndexHint_ = body->getWorldArrayIndex();
  localPoint_ = localPoint;
  path_ = nullptr;
}

void KinematicRope::setTarget(const btVector3& target) {
  requireTarget("target", target);
  driver_ = Driver::kTarget;
  target_ = toVec(target);
  body_ = nullptr;
  path_ = nullptr;
}

void KinematicRope::followPath(std::function<btVector3(double)> path) {
  if (!path) throw InvalidArgument("path", "empty std::function", "must be callable");
  driver_ = Driver::kPath;
  path_ = std::move(path);
  body_ = nullptr;
}

void KinematicRope::hold() {
  driver_ = Driver::kHold;
  body_ = nullptr;
  path_ = nullptr;
}

btVector3 KinematicRope::leadingEnd() const { return toBullet(rope_.leadingEnd()); }

Capsule KinematicRope::capsule(int i) const {
  if (i < 0 || i >= capsuleCount()) {
    throw InvalidArgument("i", std::to_string(i), "must be in [0, " + std::to_string(capsuleCount()) + ")");
  }
  Capsule capsule;
  capsule.a = axis_[static_cast<std::size_t>(i)];
  capsule.b = axis_[static_cast<std::size_t>(i) + 1];
  capsule.radius = static_cast<btScalar>(settings_.radius);
  return capsule;
}

std::pair<double, double> KinematicRope::capsuleParameters(int i) const {
  capsule(i);  // checks i
  return {ends_[static_cast<std::size_t>(i)], ends_[static_cast<std::size_t>(i) + 1]};
}

btVector3 KinematicRope::surfaceVelocity(int i, const btVector3& point) const {
  const Capsule axis = capsule(i);  // checks i
  static const char* const kAxes[3] = {"point.x", "point.y", "point.z"};
  for (int c = 0; c < 3; ++c) requireFinite(kAxes[c], static_cast<double>(point[c]));
  const double h = moveStep_;
  if (h == 0.0) return btVector3(0, 0, 0);
  const btVector3 along = axis.b - axis.a;
  const btScalar length2 = along.length2();
  const btScalar t = length2 > 0 ? btClamped((point - axis.a).dot(along) / length2, btScalar(0), btScalar(1)) : btScalar(0);
  const std::size_t k = static_cast<std::size_t>(i);
  const btVector3 velocityA = (axis_[k] - previousAxis_[k]) / static_cast<btScalar>(h);
  const btVector3 velocityB = (axis_[k + 1] - previousAxis_[k + 1]) / static_cast<btScalar>(h);
  return velocityA + (velocityB - velocityA) * t;
}

KinematicRope* KinematicRope::ropeOf(const btCollisionObject& object) {
  if (object.getUserIndex2() != kKinematicRopeTag) return nullptr;
  return static_cast<KinematicRope*>(object.getUserPointer());
}

bool KinematicRope::driverTarget(Vec3& target) {
  switch (driver_) {
    case Driver::kHold:
      return false;
    case Driver::kTarget:
      target = target_;
      return true;
    case Driver::kBody:
      // Compared by pointer only: a body removed from the world may have been deleted.
      if (!isInWorld(*world_, body_, bodyIndexHint_)) {
        report_.targetFailure = "the followed body is not in the rope's world";
        ++warnings_.targetFailures;
        return false;
      }
      target = toVec(body_->getCenterOfMassTransform() * localPoint_);
      break;
    case Driver::kPath: {
      bool threw = false;
      guardedCall([&] { target = toVec(path_(time_)); },
                  [&](const char* message) {
                    threw = true;
                    lastError_ = message;
                    report_.targetFailure = "the path function threw an exception (KinematicRope::lastError())";
                    ++warnings_.pathExceptions;
                    ++warnings_.targetFailures;
                  });
      if (threw) return false;
      break;
    }
  }
  if (!acceptable(target)) {
    report_.targetFailure = driver_ == Driver::kBody ? "the followed body's point is not finite"
                                                     : "the path returned a non-finite or too distant point";
    ++warnings_.targetFailures;
    return false;
  }
  return true;
}

void KinematicRope::substep(double h) {
  report_.substep += 1;
  report_.timeStep = h;
  report_.failure = nullptr;
  report_.targetFailure = nullptr;
  report_.unsupportedBodies = 0;
  report_.maxPenetration = 0.0;
  report_.totalImpulse.setZero();
  report_.contacts.clear();
  if (!(std::isfinite(h) && h > 0.0)) {
    report_.failure = "the substep's time step is not finite and > 0: the rope did not move";
    ++warnings_.skippedSubsteps;
    moveStep_ = 0.0;
    return;
  }
  time_ += h;
  report_.time = time_;
  moveAndPush(h);
  warnings_.unsupportedBodies += report_.unsupportedBodies;
}

void KinematicRope::recoverFromException(const char* message) noexcept {
  ++warnings_.exceptions;
  try {
    lastError_ = message;
  } catch (...) {
    // out of memory for the message: the count is what matters
  }
  report_.failure = "an exception was thrown in the rope's substep (KinematicRope::lastError())";
  moveStep_ = 0.0;
}

void KinematicRope::moveAndPush(double h) {

  // The curve before the move (copies into the existing capacity once the counts have settled).
  previousKnots_ = rope_.knots();
  previousPoints_ = rope_.controlPoints();
  Vec3 target;
  if (driverTarget(target) && target != rope_.leadingEnd()) rope_.moveLeadingEnd(target);

  rebuildCapsules(true);
  moveStep_ = h;
  if (world_ == nullptr) return;
  findCandidates();
  push(h);
}

void KinematicRope::rebuildCapsules(bool swept) {
  // Capsule ends: every non-empty span in capsulesPerSpan equal parameter pieces (one for polylines).
  const KnotVector& knots = rope_.knots();
  capsuleEnds(knots, knots.validBegin(), knots.validEnd(), rope_.degree() == 1 ? 1 : settings_.capsulesPerSpan, ends_);
  const std::size_t count = ends_.size() - 1;

  const PointList& points = rope_.controlPoints();
  axis_.resize(ends_.size());
  previousAxis_.resize(ends_.size());
  bulge_.resize(count);
  const double previousBegin = previousKnots_.validBegin();
  const double previousEnd = previousKnots_.validEnd();
  for (std::size_t i = 0; i < ends_.size(); ++i) {
    axis_[i] = toBullet(curvePosition(knots, points, ends_[i]));
    const double s = std::clamp(ends_[i], previousBegin, previousEnd);
    previousAxis_[i] = swept ? toBullet(curvePosition(previousKnots_, previousPoints_, s)) : axis_[i];
  }
  for (std::size_t i = 0; i < count; ++i) {
    const btVector3 middle = toBullet(curvePosition(knots, points, 0.5 * (ends_[i] + ends_[i + 1])));
    bulge_[i] = (middle - (axis_[i] + axis_[i + 1]) * btScalar(0.5)).length();
  }

  // The compound follows the count (adaptivity adds and removes spans). Each leaf covers the capsule
  // before and after this substep's move, padded by the radius, the speculative margin and the
  // curve's bulge over the chord.
  proxies_.rebuild(ends_, axis_);
  report_.oversizedBoxes = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const int child = static_cast<int>(i);
    proxies_.placeCapsule(child);
    btVector3 lo = axis_[i], hi = axis_[i];
    for (const btVector3* p : {&axis_[i + 1], &previousAxis_[i], &previousAxis_[i + 1]}) {
      lo.setMin(*p);
      hi.setMax(*p);
    }
    const btScalar pad = static_cast<btScalar>(settings_.radius + settings_.speculativeMargin) + bulge_[i];
    lo -= btVector3(pad, pad, pad);
    hi += btVector3(pad, pad, pad);
    if (!proxies_.fitLeaf(child, lo, hi)) ++report_.oversizedBoxes;  // keeps its previous leaf
  }
  if (!proxies_.fitObjectBox()) report_.oversizedBoxes = static_cast<int>(count);  // keeps its previous box
}

void KinematicRope::findCandidates() {
  // Bodies overlapping each capsule (padded by the speculative margin), straight from the broadphase's
  // current boxes: exact for this substep whatever the driver did, unlike the pair cache, which was
  // computed before the move.
  struct Collector : btBroadphaseAabbCallback {
    KinematicRope* rope = nullptr;
    int capsule = 0;
    bool process(const btBroadphaseProxy* proxy) override {
      if (btRigidBody* body = pushableBody(*proxy, rope->settings_.collisionGroup, rope->settings_.collisionMask,
                                           rope->body_)) {
        rope->candidates_.push_back(Candidate{body->getWorldArrayIndex(), capsule, body});
      }
      return true;
    }
  } collector;
  collector.rope = this;
  candidates_.clear();
  btBroadphaseInterface* broadphase = world_->getBroadphase();
  const btScalar pad = static_cast<btScalar>(settings_.radius + settings_.speculativeMargin);
  for (int i = 0; i < capsuleCount(); ++i) {
    const std::size_t k = static_cast<std::size_t>(i);
    btVector3 lo = axis_[k], hi = axis_[k];
    lo.setMin(axis_[k + 1]);
    hi.setMax(axis_[k + 1]);
    const btVector3 padding(pad + bulge_[k], pad + bulge_[k], pad + bulge_[k]);
    collector.capsule = i;
    broadphase->aabbTest(lo - padding, hi + padding, collector);
  }
  // A fixed order (broadphase order depends on its tree and on pointers): by body, then along the rope.
  std::sort(candidates_.begin(), candidates_.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.worldIndex, a.capsule) < std::tie(b.worldIndex, b.capsule);
  });
  candidates_.erase(std::unique(candidates_.begin(), candidates_.end(),
                                [](const Candidate& a, const Candidate& b) {
                                  return a.worldIndex == b.worldIndex && a.capsule == b.capsule;
                                }),
                    candidates_.end());
}

void KinematicRope::push(double h) {
  OneWayContactLaw law;
  law.penetrationRecovery = settings_.penetrationRecovery;
  law.friction = settings_.friction;
  law.iterations = settings_.solverIterations;
  // Candidates are sorted by body: gather each body's contacts over all capsules, solve them together.
  std::size_t first = 0;
  while (first < candidates_.size()) {
    btRigidBody* body = candidates_[first].body;
    std::size_t last = first;
    while (last < candidates_.size() && candidates_[last].body == body) ++last;
    bodyContacts_.clear();
    bool unsupported = !bodyStateFinite(*body);  // a NaN body gets no (NaN) impulse
    for (std::size_t c = first; c < last && !unsupported; ++c) {
      const int capsuleIndex = candidates_[c].capsule;
      const std::size_t k = static_cast<std::size_t>(capsuleIndex);
      scratch_.clear();
      try {
        findContacts(capsule(capsuleIndex), *body, settings_.speculativeMargin, scratch_);
      } catch (const InvalidArgument&) {
        unsupported = true;  // a shape the narrowphase does not handle; nothing may throw out of Bullet's step
        break;
      }
      for (const Contact& contact : scratch_) {
        if (!finiteContact(contact)) unsupported = true;  // e.g. a body with a non-finite transform
      }
      if (unsupported) break;
      const btVector3 velocityA = (axis_[k] - previousAxis_[k]) / static_cast<btScalar>(h);
      const btVector3 velocityB = (axis_[k + 1] - previousAxis_[k + 1]) / static_cast<btScalar>(h);
      for (const Contact& contact : scratch_) {
        OneWayContact entry;
        entry.contact = contact;
        // The rope's velocity at the contact over this substep, linear along the capsule.
        entry.ropeVelocity = velocityA + (velocityB - velocityA) * contact.t;
        bodyContacts_.push_back(entry);
        KinematicContactRecord record;
        record.body = body;
        record.capsule = capsuleIndex;
        record.s = ends_[k] + static_cast<double>(contact.t) * (ends_[k + 1] - ends_[k]);
        record.point = contact.pointOnBody;
        record.normal = contact.normal;
        record.depth = -static_cast<double>(contact.distance);
        report_.maxPenetration = std::max(report_.maxPenetration, record.depth);
        report_.contacts.push_back(record);
      }
    }
    if (unsupported) {
      ++report_.unsupportedBodies;
      report_.contacts.resize(report_.contacts.size() - bodyContacts_.size());
    } else if (!bodyContacts_.empty()) {
      solveOneWayContacts(*body, bodyContacts_.data(), static_cast<int>(bodyContacts_.size()), h, law);
      const std::size_t base = report_.contacts.size() - bodyContacts_.size();
      for (std::size_t i = 0; i < bodyContacts_.size(); ++i) {
        report_.contacts[base + i].impulse = bodyContacts_[i].impulse();
        report_.totalImpulse += bodyContacts_[i].impulse();
      }
    }
    first = last;
  }
}

}  // namespace rope::bullet
