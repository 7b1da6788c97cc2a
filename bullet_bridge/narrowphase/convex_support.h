// SPDX-License-Identifier: MIT
#pragma once
// A supported convex Bullet shape, described as a convex *core* swept by a ball of radius
// `rounding`, in the shape's local frame. Splitting the rounding off keeps distance queries exact
// and fast: the distance to the shape is the distance to the core minus `rounding`, and the cores
// are a point, a segment or polytopes except for cylinders and cones.
//
// Shape conventions (Bullet collision margins), all with the shape's local scaling applied:
//  * btSphereShape: core = the origin, rounding = radius (a sphere's margin is its radius).
//  * btCapsuleShape{,X,Z}: core = the axis segment of length 2*halfHeight along the up axis,
//    rounding = radius.
//  * btBoxShape: core = the sharp box with half extents getHalfExtentsWithoutMargin() + margin,
//    i.e. the box the user constructed, rounding = 0. (Bullet's own GJK rounds its edges by the
//    margin; the rope sees the sharp box.)
//  * btCylinderShape{,X,Z}: core = the sharp circular cylinder of radius getRadius() and half
//    height getHalfExtentsWithMargin()[upAxis] (the dimensions the user constructed), rounding = 0.
//  * btConeShape{,X,Z}: core = the sharp cone (apex at +height/2 on the up axis, base of radius
//    getRadius() at -height/2), rounding = margin, because Bullet does not shrink a cone by its
//    margin but collides with the cone inflated by it.
//  * btConvexHullShape: core = the hull of the scaled points, rounding = margin (likewise inflated).

#include <BulletCollision/CollisionShapes/btCollisionShape.h>
#include <LinearMath/btVector3.h>

#include "bullet_bridge/bullet_precision.h"

class btConvexHullShape;

namespace rope::bullet {

struct ConvexCore {
  enum class Kind { Point, Segment, Box, Cylinder, Cone, Hull };

  Kind kind = Kind::Point;
  int upAxis = 1;                     // Segment, Cylinder, Cone: 0 = x, 1 = y, 2 = z
  btVector3 halfExtents{0, 0, 0};     // Box: half extents, m
  btScalar halfHeight = 0;            // Segment, Cylinder, Cone: half the length along upAxis, m
  btScalar radius = 0;                // Cylinder radius, Cone base radius, m
  const btConvexHullShape* hull = nullptr;  // Hull: the scaled points of this shape
  btVector3 interiorPoint{0, 0, 0};   // a point of the core (its centroid), local frame
  btScalar rounding = 0;              // radius of the ball swept over the core, m, >= 0
  btScalar size = 0;                  // bounding radius of the core about the local origin, m

  // Point of the core farthest in direction `direction` (any length, may be zero), local frame.
  btVector3 support(const btVector3& direction) const;
};

// Describes `shape` if it is one of the convex shapes above and returns true; returns false for
// any other shape (compounds, concave shapes and unsupported convex shapes).
bool makeConvexCore(const btCollisionShape& shape, ConvexCore& core);

}  // namespace rope::bullet
