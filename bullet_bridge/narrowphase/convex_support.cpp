// SPDX-License-Identifier: MIT
#include "bullet_bridge/narrowphase/convex_support.h"

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btConeShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>

#include <cmath>

namespace rope::bullet {

namespace {

// Ties (a zero component) pick the positive side, so the support is a deterministic vertex.
btScalar signOf(btScalar x) { return x < 0 ? btScalar(-1) : btScalar(1); }

// Direction of `d` orthogonal to `axis`, scaled to length `radius`; zero if `d` is along the axis.
btVector3 radialSupport(const btVector3& d, int axis, btScalar radius) {
  btVector3 radial = d;
  radial[axis] = 0;
  const btScalar length = radial.length();
  if (!(length > 0)) return btVector3(0, 0, 0);
  return radial * (radius / length);
}

}  // namespace

btVector3 ConvexCore::support(const btVector3& d) const {
  switch (kind) {
    case Kind::Point:
      return btVector3(0, 0, 0);
    case Kind::Segment: {
      btVector3 p(0, 0, 0);
      p[upAxis] = signOf(d[upAxis]) * halfHeight;
      return p;
    }
    case Kind::Box:
      return btVector3(signOf(d.x()) * halfExtents.x(), signOf(d.y()) * halfExtents.y(),
                       signOf(d.z()) * halfExtents.z());
    case Kind::Cylinder: {
      btVector3 p = radialSupport(d, upAxis, radius);
      p[upAxis] = signOf(d[upAxis]) * halfHeight;
      return p;
    }
    case Kind::Cone: {
      // The apex wins when d lies inside the cone of directions normal to the apex: its height
      // gain 2h*d_up exceeds the radial gain R*|d_radial| of the rim.
      btVector3 radial = d;
      radial[upAxis] = 0;
      const btScalar radialLength = radial.length();
      btVector3 p(0, 0, 0);
      if (d[upAxis] * 2 * halfHeight > radius * radialLength) {
        p[upAxis] = halfHeight;
        return p;
      }
      if (radialLength > 0) p = radial * (radius / radialLength);
      p[upAxis] = -halfHeight;
      return p;
    }
    case Kind::Hull: {
      const int n = hull->getNumPoints();
      btVector3 best = hull->getScaledPoint(0);
      btScalar bestDot = best.dot(d);
      for (int i = 1; i < n; ++i) {
        const btVector3 p = hull->getScaledPoint(i);
        const btScalar dot = p.dot(d);
        if (dot > bestDot) {
          bestDot = dot;
          best = p;
        }
      }
      return best;
    }
  }
  return btVector3(0, 0, 0);
}

bool makeConvexCore(const btCollisionShape& shape, ConvexCore& core) {
  core = ConvexCore();
  switch (shape.getShapeType()) {
    case SPHERE_SHAPE_PROXYTYPE: {
      const auto& sphere = static_cast<const btSphereShape&>(shape);
      core.kind = ConvexCore::Kind::Point;
      core.rounding = sphere.getRadius();
      core.size = 0;
      return true;
    }
    case CAPSULE_SHAPE_PROXYTYPE: {
      const auto& capsule = static_cast<const btCapsuleShape&>(shape);
      core.kind = ConvexCore::Kind::Segment;
      core.upAxis = capsule.getUpAxis();
      core.halfHeight = capsule.getHalfHeight();
      core.rounding = capsule.getRadius();
      core.size = core.halfHeight;
      return true;
    }
    case BOX_SHAPE_PROXYTYPE: {
      const auto& box = static_cast<const btBoxShape&>(shape);
      core.kind = ConvexCore::Kind::Box;
      core.halfExtents = box.getHalfExtentsWithoutMargin() +
                         btVector3(box.getMargin(), box.getMargin(), box.getMargin());
      core.size = core.halfExtents.length();
      return true;
    }
    case CYLINDER_SHAPE_PROXYTYPE: {
      const auto& cylinder = static_cast<const btCylinderShape&>(shape);
      core.kind = ConvexCore::Kind::Cylinder;
      core.upAxis = cylinder.getUpAxis();
      core.radius = cylinder.getRadius();
      core.halfHeight = cylinder.getHalfExtentsWithMargin()[core.upAxis];
      core.size = std::sqrt(core.radius * core.radius + core.halfHeight * core.halfHeight);
      return true;
    }
    case CONE_SHAPE_PROXYTYPE: {
      const auto& cone = static_cast<const btConeShape&>(shape);
      core.kind = ConvexCore::Kind::Cone;
      core.upAxis = cone.getConeUpIndex();
      core.radius = cone.getRadius();
      core.halfHeight = cone.getHeight() / 2;
      core.rounding = cone.getMargin();
      core.size = std::sqrt(core.radius * core.radius + core.halfHeight * core.halfHeight);
      return true;
    }
    case CONVEX_HULL_SHAPE_PROXYTYPE: {
      const auto& hull = static_cast<const btConvexHullShape&>(shape);
      if (hull.getNumPoints() < 1) return false;
      core.kind = ConvexCore::Kind::Hull;
      core.hull = &hull;
      core.rounding = hull.getMargin();
      btVector3 sum(0, 0, 0);
      btScalar size = 0;
      for (int i = 0; i < hull.getNumPoints(); ++i) {
        const btVector3 p = hull.getScaledPoint(i);
        sum += p;
        size = std::max(size, p.length());
      }
      core.interiorPoint = sum / btScalar(hull.getNumPoints());
      core.size = size;
      return true;
    }
    default:
      return false;
  }
}

}  // namespace rope::bullet
