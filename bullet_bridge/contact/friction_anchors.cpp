// SPDX-License-Identifier: MIT
#include "bullet_bridge/contact/friction_anchors.h"
#include "bullet_bridge/detail/bullet_math.h"
#include "rope/common/prefetch.h"

#include <algorithm>
#include <functional>

namespace rope::bullet {

namespace {

// Bodies ordered by address: only the grouping by body matters, never the order between bodies, so
// results do not depend on where the allocator put them.
bool before(const FrictionAnchor& x, const btCollisionObject* body, double s) {
  if (x.body != body) return std::less<const btCollisionObject*>()(x.body, body);
  return x.s < s;
}

}  // namespace

bool FrictionAnchors::find(const btCollisionObject& body, double s, double reach, const Rod& rod, btVector3& anchor,
                           bool& sliding, double& pressure) const {
  const auto next = std::lower_bound(anchors_.begin(), anchors_.end(), s,
                                     [&](const FrictionAnchor& x, double value) { return before(x, &body, value); });
  const FrictionAnchor* right = (next != anchors_.end() && next->body == &body && next->s - s <= reach) ? &*next : nullptr;
  const FrictionAnchor* left = nullptr;
  if (next != anchors_.begin()) {
    const FrictionAnchor& previous = *(next - 1);
    if (previous.body == &body && s - previous.s <= reach) left = &previous;
  }
  const btTransform& frame = body.getWorldTransform();
  if (left != nullptr && right != nullptr && right->s > left->s) {
    const btScalar t = static_cast<btScalar>((s - left->s) / (right->s - left->s));
    anchor = frame * (left->localPoint + (right->localPoint - left->localPoint) * t);
    sliding = (t < btScalar(0.5) ? left : right)->sliding;
    pressure = left->pressure + (right->pressure - left->pressure) * static_cast<double>(t);
    return true;
  }
  const FrictionAnchor* only = left != nullptr ? left : right;
  if (only == nullptr) return false;
  // One side only: the anchor moves rigidly with the rope from the stored one.
  anchor = frame * only->localPoint + toBullet(rod.position(s) - rod.position(only->s));
  sliding = only->sliding;
  pressure = only->pressure;
  return true;
}

void FrictionAnchors::commit() {
  std::sort(next_.begin(), next_.end(),
            [](const FrictionAnchor& x, const FrictionAnchor& y) { return before(x, y.body, y.s); });
  anchors_.swap(next_);
  next_.clear();
}

void FrictionAnchors::clear() {
  anchors_.clear();
  next_.clear();
}

void FrictionAnchors::prefetch() const { prefetchVector(anchors_); }

}  // namespace rope::bullet
