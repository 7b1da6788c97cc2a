// SPDX-License-Identifier: MIT
#include "bullet_bridge/rope_debug_draw.h"

#include <string>

#include "bullet_bridge/detail/bullet_math.h"
#include "bullet_bridge/rope_world.h"
#include "rope/common/error.h"

namespace rope::bullet {

namespace {

// A capsule's transform for btIDebugDraw::drawCapsule (axis along local y, centred).
btTransform capsuleFrame(const btVector3& a, const btVector3& b) {
  btTransform frame;
  frame.setIdentity();
  frame.setOrigin((a + b) * btScalar(0.5));
  const btVector3 axis = b - a;
  const btScalar length = axis.length();
  if (length > btScalar(0)) {
    const btVector3 y(0, 1, 0);
    const btVector3 direction = axis / length;
    const btVector3 cross = y.cross(direction);
    const btScalar sine = cross.length();
    if (sine > btScalar(1e-6)) {
      frame.setRotation(btQuaternion(cross / sine, btAtan2(sine, y.dot(direction))));
    } else if (y.dot(direction) < btScalar(0)) {
      frame.setRotation(btQuaternion(btVector3(1, 0, 0), SIMD_PI));
    }
  }
  return frame;
}

}  // namespace

void drawRope(const RopeObject& rope, btIDebugDraw& drawer, int segmentsPerSpan, const RopeDebugColours& colours) {
  if (segmentsPerSpan < 1) {
    throw InvalidArgument("segmentsPerSpan", std::to_string(segmentsPerSpan), "must be >= 1");
  }
  const Rod& rod = rope.rod();
  const KnotVector& knots = rod.knots();
  double previous = rod.beginParameter();
  btVector3 last = toBullet(rod.position(previous));
  for (int i = 0; i < knots.size(); ++i) {
    const double knot = knots[i];
    if (!(knot > previous) || knot > rod.endParameter()) continue;
    for (int j = 1; j <= segmentsPerSpan; ++j) {
      const double s = j == segmentsPerSpan ? knot : previous + (knot - previous) * j / segmentsPerSpan;
      const btVector3 next = toBullet(rod.position(s));
      drawer.drawLine(last, next, colours.curve);
      last = next;
    }
    previous = knot;
  }

  const int mode = drawer.getDebugMode();
  if ((mode & btIDebugDraw::DBG_DrawWireframe) != 0) {
    const CapsuleProxies& proxies = rope.proxies();
    for (int i = 0; i < proxies.size(); ++i) {
      const Capsule capsule = proxies.capsule(i);
      drawer.drawCapsule(capsule.radius, btScalar(0.5) * (capsule.b - capsule.a).length(), 1,
                         capsuleFrame(capsule.a, capsule.b), colours.capsules);
    }
  }
  if ((mode & btIDebugDraw::DBG_DrawContactPoints) != 0) {
    for (const RopeContactRecord& contact : rope.contacts()) {
      drawer.drawContactPoint(contact.point, contact.normal, static_cast<btScalar>(-contact.depth), 1,
                              contact.active ? colours.activeContact : colours.speculativeContact);
    }
  }
}

void drawRopes(const RopeWorld& world, btIDebugDraw& drawer) {
  for (const RopeObject* rope : world.ropes()) drawRope(*rope, drawer);
}

}  // namespace rope::bullet
