// SPDX-License-Identifier: MIT
#include "bullet_bridge/detail/world_membership.h"

namespace rope::bullet {

bool isInWorld(const btCollisionWorld& world, const btCollisionObject* object, int& hint) {
  if (object == nullptr) return false;
  const btCollisionObjectArray& objects = world.getCollisionObjectArray();
  if (hint >= 0 && hint < objects.size() && objects[hint] == object) return true;
  for (int i = 0; i < objects.size(); ++i) {
    if (objects[i] == object) {
      hint = i;
      return true;
    }
  }
  hint = -1;
  return false;
}

}  // namespace rope::bullet
