// SPDX-License-Identifier: MIT
#include "demos/scenes/hanging_box.h"

namespace rope::demos {

HangingBox hangBox(PhysicsWorld& physics, const HangingBoxSettings& settings, const Vec3& top, const Vec3& bottom) {
  HangingBox rig;
  const btScalar half = static_cast<btScalar>(settings.boxHalfExtent);
  rig.box = physics.addBox(btVector3(half, half, half), settings.boxMass, toBullet(bottom) - btVector3(0, half, 0));
  rig.box->setActivationState(DISABLE_DEACTIVATION);
  RodSettings rod = settings.rod;
  rod.restLength = settings.ropeLength;
  rig.rope = std::make_unique<bullet::RopeObject>(Rod::fromSegment(rod, top, bottom), settings.bridge);
  physics.ropes().addRope(*rig.rope);
  rig.pin = rig.rope->attachToPoint(rig.rope->rod().beginParameter(), toBullet(top));
  rig.boxAttachment =
      rig.rope->attachToBody(rig.rope->rod().endParameter(), *rig.box, btVector3(0, half, 0), settings.attachment);
  return rig;
}

}  // namespace rope::demos
