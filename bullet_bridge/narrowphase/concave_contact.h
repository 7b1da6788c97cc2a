// SPDX-License-Identifier: MIT
#pragma once
// Capsule vs concave Bullet shapes.
//
//  * btStaticPlaneShape, analytically: the half-space n.x <= c of the shape's local frame (as in
//    Bullet's btConvexPlaneCollisionAlgorithm, the plane's margin is not added). One contact per
//    capsule endpoint within the margin (t = 0 and t = 1; one contact if the axis is a point), so a
//    capsule lying on the plane is supported at both ends.
//  * Any other btConcaveShape (btBvhTriangleMeshShape, btScaledBvhTriangleMeshShape,
//    btHeightfieldTerrainShape, ...): every triangle the shape reports through processAllTriangles
//    over the capsule's local AABB grown by radius + margin + shape margin, each triangle inflated
//    by the shape's collision margin (Bullet collides with triangles inflated by it too). At most
//    one contact per triangle: the closest points of the axis and the triangle (exact, see
//    segment_triangle_distance.h). Triangles are two-sided. If the axis passes through a
//    triangle's interior, the contact pushes the rope back along the triangle normal towards the
//    side holding the larger part of the axis: depth = the other endpoint's depth below the
//    triangle's plane + radius + margin, at that endpoint (t = 0 or 1).

#include <BulletCollision/CollisionShapes/btConcaveShape.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>
#include <LinearMath/btTransform.h>

#include <vector>

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/capsule.h"
#include "bullet_bridge/contact.h"

namespace rope::bullet {

// Appends the contacts with distance <= margin. Preconditions (checked by findContacts): capsule
// valid, margin finite and >= 0.
void planeContacts(const Capsule& capsule, const btStaticPlaneShape& plane,
                   const btTransform& shapeToWorld, btScalar margin, std::vector<Contact>& out);
void triangleMeshContacts(const Capsule& capsule, const btConcaveShape& shape,
                          const btTransform& shapeToWorld, btScalar margin,
                          std::vector<Contact>& out);

// One triangle (a, b, c) inflated by `triangleMargin` against the capsule, all in one frame.
// Fills `contact` (indices left at -1) and returns true if its distance is <= margin.
bool triangleContact(const Capsule& capsule, const btVector3& a, const btVector3& b,
                     const btVector3& c, btScalar triangleMargin, btScalar margin,
                     Contact& contact);

}  // namespace rope::bullet
