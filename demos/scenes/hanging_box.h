// SPDX-License-Identifier: MIT
#pragma once
// The crane, winch and cut scenes' rig: a cube hanging from a rope whose top end is pinned at a world
// point. The rope runs straight from `top` to `bottom`, where the centre of the cube's top face is;
// its top end is held by attachToPoint and its bottom end is attached to the cube (two-way).

#include <memory>

#include "bullet_bridge/rope_object.h"
#include "demos/scenes/physics_world.h"
#include "rope/rod/rod.h"

namespace rope::demos {

struct HangingBox {
  btRigidBody* box = nullptr;  // owned by the PhysicsWorld
  std::unique_ptr<bullet::RopeObject> rope;
  int pin = 0;            // the top's attachment (RopeObject::attachToPoint)
  int boxAttachment = 0;  // the bottom's (RopeObject::attachToBody)
};

// The scenes fill it from their own settings (the defaults are the crane's box and rope length).
struct HangingBoxSettings {
  double ropeLength = 1.0;     // m, > 0: the rope's rest length (the distance from top to bottom)
  double boxMass = 10.0;       // kg, > 0
  double boxHalfExtent = 0.1;  // m, > 0 (a cube)
  RodSettings rod;             // restLength is set to ropeLength
  bullet::BulletRopeSettings bridge;
  bullet::AttachmentSettings attachment;
};

// Adds the box (kept awake) and the rope to `physics`, in that order. The scenes validate the settings.
HangingBox hangBox(PhysicsWorld& physics, const HangingBoxSettings& settings, const Vec3& top, const Vec3& bottom);

}  // namespace rope::demos
