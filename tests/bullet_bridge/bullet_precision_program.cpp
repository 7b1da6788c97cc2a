// SPDX-License-Identifier: MIT
// Links only if it was compiled with the Bullet precision of the bullet_bridge library it is linked
// against (see bullet_bridge/bullet_precision.h).
#include "bullet_bridge/capsule.h"

int main() {
  rope::bullet::Capsule capsule;
  return capsule.radius == btScalar(0) ? 0 : 1;
}
