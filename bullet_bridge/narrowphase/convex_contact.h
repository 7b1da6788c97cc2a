// SPDX-License-Identifier: MIT
#pragma once
// Capsule vs a convex Bullet shape (convex_support.h).
//
// A capsule is its axis segment swept by a ball, and the shape is its core swept by a ball, so
// their signed distance is dist(axis, core) - capsule.radius - core.rounding whenever the axis
// stays outside the core. That case (every speculative contact and every penetration shallower
// than the capsule radius plus the rounding) is computed exactly by GJK
// (segment_convex_distance.h). Only when the axis itself enters the core does the query fall back
// to libccd's MPR on the capsule inflated by `margin` against the full shape: distance =
// margin - MPR depth. MPR measures the depth where the ray between two interior points leaves
// the Minkowski difference; we start that ray at the axis point nearest the body's centre, so it
// is perpendicular to the rope unless that point is an end of the axis. The deep case is
// therefore an estimate: exact when the minimum translation runs along that ray (e.g. a body
// centred under the rope, a face contact), otherwise larger than the minimum translation.
//
// MPR alone is not exact even for shallow contacts: with the segment midpoint as the capsule's
// centre, a sphere of radius 0.5 overlapping a 2 m capsule of radius 0.2 near one end, its centre
// 0.25 from the axis, came out 0.676 deep instead of 0.45 (libccd 2.1). Hence GJK for every case
// the axis does not enter.

#include <LinearMath/btTransform.h>

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/capsule.h"
#include "bullet_bridge/contact.h"
#include "bullet_bridge/narrowphase/convex_support.h"

namespace rope::bullet {

// Fills `contact` (childIndex, partIndex, triangleIndex left at -1) and returns true if the signed
// distance between `capsule` (world frame) and `core` placed by `coreToWorld` is <= margin.
// Preconditions (checked by findContacts): capsule valid, margin finite and >= 0.
bool convexContact(const Capsule& capsule, const ConvexCore& core, const btTransform& coreToWorld,
                   btScalar margin, Contact& contact);

}  // namespace rope::bullet
