// SPDX-License-Identifier: MIT
#pragma once
// The stick state of rope-body friction, carried from one substep to the next along the curve.
//
// A sample of a line contact that sticks is held by a tangential spring to its anchor: the body point
// (in the body's frame, so it moves with the body) where that piece of rope began to stick. Samples
// are not material points (they are Gauss nodes of the capsule pieces, which move in the parameter
// whenever knots are inserted or removed), so the anchors are a field along the curve parameter s,
// which *is* material (insertion and removal keep the parametrisation): a new sample at s takes the
// anchor interpolated linearly between the stored anchors on either side of s on the same body, or
// moved rigidly with the rope from the one nearest anchor if only one side has one. Sliding samples
// store an anchor that puts their spring at the friction force they ended the step with, plus a flag,
// so they start the next substep sliding, or stick again still carrying their load (docs/method.md
// §11, eq. 33).
//
// Not API: installed only because body_contacts.h includes it; may change in any release.

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <LinearMath/btVector3.h>

#include <vector>

#include "bullet_bridge/bullet_precision.h"
#include "rope/rod/rod.h"

namespace rope::bullet {

struct FrictionAnchor {
  const btCollisionObject* body = nullptr;
  double s = 0.0;                  // curve parameter of the sample that stored it
  btVector3 localPoint{0, 0, 0};   // the anchor in the body's frame, m
  bool sliding = false;            // the sample was sliding at the end of its substep
  double pressure = 0.0;           // its normal force per metre of rope at the end of the substep, N/m
};

class FrictionAnchors {
 public:
  void prefetch() const;  // cache hints for the stored anchors (rope/common/prefetch.h)
  // The anchor for a sample at s on body (world frame, at the body's current transform), from the
  // stored anchors within `reach` (parameter units) of s. Returns false if there is none.
  bool find(const btCollisionObject& body, double s, double reach, const Rod& rod, btVector3& anchor,
            bool& sliding, double& pressure) const;

  // Builds the next substep's store: add() the anchors in any order, then commit() replaces the
  // stored ones (the old ones are still read by find() until then).
  void add(const FrictionAnchor& anchor) { next_.push_back(anchor); }
  void commit();
  void clear();
  int size() const { return static_cast<int>(anchors_.size()); }

 private:
  std::vector<FrictionAnchor> anchors_;  // sorted by (body, s)
  std::vector<FrictionAnchor> next_;
};

}  // namespace rope::bullet
