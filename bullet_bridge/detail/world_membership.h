// SPDX-License-Identifier: MIT
#pragma once
// Is a body still in the Bullet world? Bullet has no removal callback, and users remove a body and
// delete it between two steps, so a pointer a rope kept (an attachment, a followed body) may point to
// freed memory. The only sound test compares the pointer with the world's collision objects without
// dereferencing it (comparing an invalid pointer value is implementation-defined, not undefined, in
// C++17 [basic.stc]/4, and plain address comparison on every supported platform).
//
// Limit: if the body was deleted and a new collision object was allocated at the same address and
// added to the world, the new object is taken for the old one. Nothing short of a removal callback
// can tell the two apart; Bullet's own rule is to remove the attachment before deleting the body.

#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>

#include "bullet_bridge/bullet_precision.h"

namespace rope::bullet {

// Whether `object` is one of world's collision objects. `hint` is the index where it was last seen in
// world.getCollisionObjectArray() (or -1): checked first, O(1); otherwise the array is searched,
// O(objects), and hint updated (Bullet moves the last object into a removed object's slot, so the
// index of a body changes only when objects are removed).
bool isInWorld(const btCollisionWorld& world, const btCollisionObject* object, int& hint);

}  // namespace rope::bullet
