#pragma once
// Capsule vs a convex Bullet shape (convex_support.h).
//
// A capsule is its axis segment swept by a ball, and the shape is its core swept by a ball, so
// their signed distance is dist(axis, core) - capsule.radius - core.rounding whenever the axis
// stays outside the core. That case (every speculative contact and every penetration shallower
// than the capsule radius plus the rounding) is computed exactly by GJK
// (segment_convex_distance.h). Only when the axis itself enters the core does the query fall back
// to libccd's MPR on the capsule inflated by `margin` against the full shape: distance =
// margin - MPR depth. MPR measures the depth on the portal crossed by the ray between the two
// centres, so that deep case is an estimate (it is exact when the centre ray runs along the
// minimum-translation direction, e.g. a face contact), not the minimum translation distance.

#include <LinearMath/btTransform.h>

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/capsule.h"
#include "bullet_bridge/contact.h"
#include "bullet_bridge/convex_support.h"

namespace rope::bullet {

// Fills `contact` (childIndex, partIndex, triangleIndex left at -1) and returns true if the signed
// distance between `capsule` (world frame) and `core` placed by `coreToWorld` is <= margin.
// Preconditions (checked by findContacts): capsule valid, margin finite and >= 0.
bool convexContact(const Capsule& capsule, const ConvexCore& core, const btTransform& coreToWorld,
                   btScalar margin, Contact& contact);

}  // namespace rope::bullet
