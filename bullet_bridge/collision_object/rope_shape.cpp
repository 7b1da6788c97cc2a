// SPDX-License-Identifier: MIT
#include "bullet_bridge/collision_object/rope_shape.h"

#include <BulletCollision/BroadphaseCollision/btBroadphaseProxy.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btContinuousConvexCollision.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btRaycastCallback.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#include <LinearMath/btAabbUtil2.h>

#include <cmath>

#include "bullet_bridge/narrowphase/ray_capsule.h"

namespace rope::bullet {

namespace {

constexpr int kMeshSides = 16;       // around the axis: facets at most r (1 - cos(pi / 16)) = 2 % of r inside
constexpr int kMeshCapRings = 4;     // from each end sphere's pole to its equator
constexpr btScalar kMinNormal2 = btScalar(1e-4);  // Bullet's own test of a convex cast's normal

// Local frame: the axis runs along Y from -h to +h.
Capsule localCapsule(btScalar radius, btScalar halfHeight) {
  Capsule capsule;
  capsule.a = btVector3(0, -halfHeight, 0);
  capsule.b = btVector3(0, halfHeight, 0);
  capsule.radius = radius;
  return capsule;
}

// Outward unit normal at the surface point nearest to p on the ball of the axis point at t.
btVector3 outwardNormal(const Capsule& capsule, double t, const btVector3& p) {
  const btVector3 n = p - capsule.axisPoint(static_cast<btScalar>(t));
  const btScalar length = n.length();
  return length > btScalar(0) ? n / length : btVector3(1, 0, 0);
}

// Point `side` (of kMeshSides) on ring `ring` of the mesh: rings 0 .. kMeshCapRings run from the lower
// pole to the lower equator, the next kMeshCapRings + 1 from the upper equator to the upper pole.
btVector3 meshPoint(btScalar radius, btScalar halfHeight, int ring, int side) {
  constexpr double kPi = 3.14159265358979323846;
  const bool upper = ring > kMeshCapRings;
  const int k = upper ? ring - kMeshCapRings - 1 : ring;
  const double theta = (upper ? 0.0 : -0.5 * kPi) + 0.5 * kPi * k / kMeshCapRings;
  const double phi = 2.0 * kPi * side / kMeshSides;
  const double c = radius * std::cos(theta);
  return btVector3(static_cast<btScalar>(c * std::cos(phi)),
                   static_cast<btScalar>(radius * std::sin(theta)) + (upper ? halfHeight : -halfHeight),
                   static_cast<btScalar>(c * std::sin(phi)));
}

}  // namespace

RopeCapsuleShape::RopeCapsuleShape(btScalar radius, int index) : radius_(radius), index_(index) {
  m_shapeType = FAST_CONCAVE_MESH_PROXYTYPE;
}

void RopeCapsuleShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const {
  // The axis's box, grown by the radius: tight for any orientation.
  const btVector3 half = t.getBasis().getColumn(1).absolute() * halfHeight_ + btVector3(radius_, radius_, radius_);
  aabbMin = t.getOrigin() - half;
  aabbMax = t.getOrigin() + half;
}

void RopeCapsuleShape::processAllTriangles(btTriangleCallback* callback, const btVector3& aabbMin,
                                           const btVector3& aabbMax) const {
  const Capsule capsule = localCapsule(radius_, halfHeight_);
  if (auto* ray = dynamic_cast<btTriangleRaycastCallback*>(callback)) {
    double lambda = 0.0, t = 0.0;
    if (!rayCapsule(ray->m_from, ray->m_to - ray->m_from, capsule, lambda, t)) return;
    if (!(lambda < ray->m_hitFraction)) return;
    const btVector3 point = ray->m_from.lerp(ray->m_to, static_cast<btScalar>(lambda));
    ray->m_hitFraction = ray->reportHit(outwardNormal(capsule, t, point), static_cast<btScalar>(lambda), -1, index_);
    return;
  }
  if (auto* cast = dynamic_cast<btTriangleConvexcastCallback*>(callback)) {
    const btTransform toLocal = cast->m_triangleToWorld.inverse();
    if (cast->m_convexShape->getShapeType() == SPHERE_SHAPE_PROXYTYPE) {
      // A sphere's centre against the capsule grown by its radius: exact.
      const auto* sphere = static_cast<const btSphereShape*>(cast->m_convexShape);
      const btVector3 from = toLocal * cast->m_convexShapeFrom.getOrigin();
      const btVector3 to = toLocal * cast->m_convexShapeTo.getOrigin();
      Capsule grown = capsule;
      grown.radius += sphere->getRadius();
      double lambda = 0.0, t = 0.0;
      if (!rayCapsule(from, to - from, grown, lambda, t) || !(lambda < cast->m_hitFraction)) return;
      const btVector3 normal = outwardNormal(grown, t, from.lerp(to, static_cast<btScalar>(lambda)));
      const btVector3 point = capsule.axisPoint(static_cast<btScalar>(t)) + normal * radius_;
      // Bullet's convex cast callbacks take the normal and point in world space.
      cast->m_hitFraction = cast->reportHit(cast->m_triangleToWorld.getBasis() * normal, cast->m_triangleToWorld * point,
                                            static_cast<btScalar>(lambda), -1, index_);
      return;
    }
    // Any other convex shape: Bullet's continuous convex cast, against the same capsule as Bullet's
    // shape (what a btCapsuleShape child got before).
    const btCapsuleShape standInShape = standIn();
    btVoronoiSimplexSolver simplex;
    btGjkEpaPenetrationDepthSolver penetration;
    btContinuousConvexCollision caster(cast->m_convexShape, &standInShape, &simplex, &penetration);
    btConvexCast::CastResult result;
    result.m_fraction = btScalar(1);
    result.m_allowedPenetration = cast->m_allowedPenetration;
    if (!caster.calcTimeOfImpact(cast->m_convexShapeFrom, cast->m_convexShapeTo, cast->m_triangleToWorld,
                                 cast->m_triangleToWorld, result))
      return;
    if (!(result.m_normal.length2() > kMinNormal2) || !(result.m_fraction < cast->m_hitFraction)) return;
    result.m_normal.normalize();
    cast->m_hitFraction = cast->reportHit(result.m_normal, result.m_hitPoint, result.m_fraction, -1, index_);
    return;
  }
  // Any other callback: the closed triangle mesh, rings from pole to pole.
  btVector3 lo, hi;
  getAabb(btTransform::getIdentity(), lo, hi);
  if (!TestAabbAgainstAabb2(lo, hi, aabbMin, aabbMax)) return;
  int triangle = 0;
  for (int ring = 0; ring < 2 * kMeshCapRings + 1; ++ring) {
    for (int side = 0; side < kMeshSides; ++side) {
      const int next = (side + 1) % kMeshSides;
      const btVector3 a = meshPoint(radius_, halfHeight_, ring, side), b = meshPoint(radius_, halfHeight_, ring, next);
      const btVector3 c = meshPoint(radius_, halfHeight_, ring + 1, next), d = meshPoint(radius_, halfHeight_, ring + 1, side);
      btVector3 first[3] = {a, b, c};
      btVector3 second[3] = {a, c, d};
      // Not the degenerate ones at the poles (a ring of one point).
      if (ring > 0) callback->processTriangle(first, index_, triangle++);
      if (ring + 1 < 2 * kMeshCapRings + 1) callback->processTriangle(second, index_, triangle++);
    }
  }
}

}  // namespace rope::bullet
