// SPDX-License-Identifier: MIT
#pragma once
// Narrowphase entry point: contacts between a rope capsule and one Bullet collision object.
//
// Supported shapes: btSphereShape, btCapsuleShape{,X,Z}, btBoxShape, btCylinderShape{,X,Z},
// btConeShape{,X,Z}, btConvexHullShape (narrowphase/convex_contact.h: at most one contact), btStaticPlaneShape
// and every other btConcaveShape except btSdfCollisionShape (narrowphase/concave_contact.h: up to two plane
// contacts, one per triangle),
// and btCompoundShape of any of these, nested to any depth (children placed by their local
// transforms; Contact::childIndex is the index in the object's top-level compound). A kinematic
// rope's object (KinematicRope::collisionObject) is its capsules: closest points of the axes, one
// contact per capsule near, childIndex = the capsule.

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>

#include <vector>

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/capsule.h"
#include "bullet_bridge/contact.h"

namespace rope::bullet {

// Appends to `out` every contact between `capsule` (world frame) and `object` (at its
// getWorldTransform()) whose signed distance is <= `margin` (m): penetrations and speculative
// contacts up to `margin` before touching. Throws rope::InvalidArgument naming "capsule.a",
// "capsule.b", "capsule.radius" or "margin" for non-finite or out-of-range input, and naming
// "object.shape" with the Bullet shape type name for a shape it does not support; `out` is left
// unchanged when it throws.
void findContacts(const Capsule& capsule, const btCollisionObject& object, double margin,
                  std::vector<Contact>& out);

}  // namespace rope::bullet
