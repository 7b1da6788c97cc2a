// SPDX-License-Identifier: MIT
// Builds against the installed headers and libraries only: interpolate a path and insert a knot
// (rope), touch a Bullet sphere with a rope capsule (bullet_bridge, through Bullet of the same
// precision), and sweep a tube mesh (render, no GL context needed).
#include <btBulletCollisionCommon.h>

#include <cstdio>
#include <vector>

#include "bullet_bridge/find_contacts.h"
#include "render/tube_mesh.h"
#include "rope/spline/bspline_curve.h"
#include "rope/spline/curve_interpolation.h"

int main() {
  const rope::PointList path = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {2, 1, 1}, {3, 0, 1}};
  rope::BSplineCurve curve = rope::interpolatePolyline(path).curve;
  const double s = 0.37 * curve.endParameter();
  const rope::Vec3 before = curve.position(s);
  curve.insertKnot(0.5 * curve.endParameter());
  const double moved = (curve.position(s) - before).norm();

  btSphereShape sphere(0.5);
  btCollisionObject body;
  body.setCollisionShape(&sphere);
  rope::bullet::Capsule capsule;
  capsule.a = btVector3(-1.0, 0.55, 0.0);
  capsule.b = btVector3(1.0, 0.55, 0.0);
  capsule.radius = 0.1;
  std::vector<rope::bullet::Contact> contacts;
  rope::bullet::findContacts(capsule, body, 0.01, contacts);

  const rope::render::Mesh tube = rope::render::buildTubeMesh(curve.knots(), curve.controlPoints());

  std::printf("control points %d, moved %.3g m, contacts %zu, tube vertices %zu\n",
              curve.controlPointCount(), moved, contacts.size(), tube.vertices.size());
  const bool ok = moved < 1e-12 && curve.controlPointCount() == 6 && contacts.size() == 1 &&
                  !tube.vertices.empty();
  return ok ? 0 : 1;
}
