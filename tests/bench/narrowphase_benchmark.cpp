// SPDX-License-Identifier: MIT
// Cost of one rope-capsule narrowphase query (bullet_bridge/find_contacts.h) per shape, in three
// situations: penetrating (axis outside the body, GJK), speculative (gap inside the margin, GJK),
// separated (gap beyond the margin, GJK early exit), plus the deep case (axis inside the body,
// libccd MPR) for the box. Bodies are rotated and translated; the capsule is 0.2 m long, r = 0.02.

#include <benchmark/benchmark.h>
#include <btBulletCollisionCommon.h>

#include <memory>
#include <vector>

#include "bullet_bridge/find_contacts.h"

namespace {

using rope::bullet::Capsule;
using rope::bullet::Contact;

constexpr double kMargin = 0.01;
constexpr double kRadius = 0.02;

enum Situation { kPenetrating = 0, kSpeculative = 1, kSeparated = 2, kDeep = 3 };

// Gap between the capsule surface and the body for each situation (m). The deep case puts the
// axis 0.01 inside the body surface instead.
double gapFor(int situation) {
  switch (situation) {
    case kPenetrating: return -0.005;
    case kSpeculative: return 0.005;
    case kSeparated: return 0.05;
    default: return -kRadius - 0.01;
  }
}

btTransform bodyPlacement() {
  return btTransform(btQuaternion(btVector3(1, 2, 3).normalized(), 0.4), btVector3(0.2, 1.0, -0.5));
}

// Runs the query for a capsule lying (slightly tilted) over the body's local surface point
// `surface` with outward local normal `normal`.
void runQuery(benchmark::State& state, const btCollisionShape& shape, const btVector3& surface,
              const btVector3& normal) {
  btCollisionObject object;
  object.setCollisionShape(const_cast<btCollisionShape*>(&shape));
  object.setWorldTransform(bodyPlacement());
  const btVector3 n = normal.normalized();
  const btVector3 tangent = n.cross(btVector3(0.3, 0.1, 0.9)).normalized();
  const btVector3 centre = surface + n * (kRadius + gapFor(static_cast<int>(state.range(0))));
  Capsule capsule;
  capsule.a = bodyPlacement() * (centre - tangent * 0.1);
  capsule.b = bodyPlacement() * (centre + tangent * 0.1 + n * 0.002);
  capsule.radius = kRadius;
  std::vector<Contact> contacts;
  contacts.reserve(256);
  std::size_t found = 0;
  for (auto _ : state) {
    contacts.clear();
    rope::bullet::findContacts(capsule, object, kMargin, contacts);
    found = contacts.size();
    benchmark::DoNotOptimize(contacts.data());
  }
  state.counters["contacts"] = static_cast<double>(found);
}

void situations(benchmark::internal::Benchmark* b) {
  b->ArgName("situation")->Arg(kPenetrating)->Arg(kSpeculative)->Arg(kSeparated);
}

void BM_CapsuleBox(benchmark::State& state) {
  btBoxShape box(btVector3(0.5, 0.3, 0.4));
  runQuery(state, box, btVector3(0.1, 0.3, 0.05), btVector3(0, 1, 0));
}
BENCHMARK(BM_CapsuleBox)->Apply(situations)->Arg(kDeep);

void BM_CapsuleSphere(benchmark::State& state) {
  btSphereShape sphere(0.4);
  runQuery(state, sphere, btVector3(0, 0.4, 0), btVector3(0, 1, 0));
}
BENCHMARK(BM_CapsuleSphere)->Apply(situations);

void BM_CapsuleCylinder(benchmark::State& state) {
  btCylinderShape cylinder(btVector3(0.3, 0.5, 0.3));
  runQuery(state, cylinder, btVector3(0.3, 0.1, 0), btVector3(1, 0, 0));
}
BENCHMARK(BM_CapsuleCylinder)->Apply(situations);

void BM_CapsuleHull(benchmark::State& state) {
  // An icosahedron-like hull of 12 points on a sphere of radius 0.4 (margin 0.04 by default).
  btConvexHullShape hull;
  const double g = 1.618033988749895;
  const btVector3 points[12] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                                {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                                {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (const btVector3& p : points) hull.addPoint(p.normalized() * 0.4, false);
  hull.recalcLocalAabb();
  // Centre of the face (0,1,g)-(-1,g,0)-(1,g,0) direction, beyond the margin-inflated face.
  const btVector3 faceDirection = (points[5] + points[0] + points[1]).normalized();
  const double faceDistance = (points[5].normalized() * 0.4).dot(faceDirection);
  runQuery(state, hull, faceDirection * (faceDistance + hull.getMargin()), faceDirection);
}
BENCHMARK(BM_CapsuleHull)->Apply(situations);

void BM_CapsulePlane(benchmark::State& state) {
  btStaticPlaneShape plane(btVector3(0, 1, 0), 0.0);
  runQuery(state, plane, btVector3(0.3, 0, -0.2), btVector3(0, 1, 0));
}
BENCHMARK(BM_CapsulePlane)->Apply(situations);

void BM_CapsuleTriangleMesh(benchmark::State& state) {
  // 100 triangles: a 10 x 5 grid of 0.2 m quads with a gentle bump, in the x-z plane.
  btTriangleMesh mesh;
  auto height = [](int i, int k) { return 0.01 * ((i * 7 + k * 3) % 5); };
  for (int i = 0; i < 10; ++i) {
    for (int k = 0; k < 5; ++k) {
      const btVector3 p00(0.2 * i, height(i, k), 0.2 * k), p10(0.2 * (i + 1), height(i + 1, k), 0.2 * k);
      const btVector3 p01(0.2 * i, height(i, k + 1), 0.2 * (k + 1));
      const btVector3 p11(0.2 * (i + 1), height(i + 1, k + 1), 0.2 * (k + 1));
      mesh.addTriangle(p00, p01, p10);
      mesh.addTriangle(p10, p01, p11);
    }
  }
  btBvhTriangleMeshShape shape(&mesh, true);
  // Over the highest vertex near the middle, (1.0, h, 0.4).
  runQuery(state, shape, btVector3(1.0, height(5, 2), 0.4), btVector3(0, 1, 0));
}
BENCHMARK(BM_CapsuleTriangleMesh)->Apply(situations);

}  // namespace
