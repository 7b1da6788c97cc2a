// SPDX-License-Identifier: MIT
#include "render/shape_mesh.h"

#include <btBulletCollisionCommon.h>
#include <BulletCollision/CollisionShapes/btTriangleCallback.h>
#include <LinearMath/btConvexHullComputer.h>
#include <LinearMath/btGeometryUtil.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "render/primitive_mesh.h"
#include "rope/common/error.h"

namespace rope::render {

namespace {

Vec3 toVec3(const btVector3& v) { return Vec3(v.x(), v.y(), v.z()); }

Eigen::Isometry3d toIsometry(const btTransform& t) {
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  const btMatrix3x3& basis = t.getBasis();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) result.linear()(r, c) = basis[r][c];
  }
  result.translation() = toVec3(t.getOrigin());
  return result;
}

// The primitives are built around +Y; a cyclic permutation of the axes (a rotation, so winding and
// normals stay outward) puts that axis onto Bullet's up axis 0 (X), 1 (Y) or 2 (Z).
Eigen::Isometry3d upAxisRotation(int upAxis) {
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  if (upAxis == 0) {
    result.linear() << 0, 1, 0, 0, 0, 1, 1, 0, 0;  // y -> x, z -> y, x -> z
  } else if (upAxis == 2) {
    result.linear() << 0, 0, 1, 1, 0, 0, 0, 1, 0;  // y -> z, z -> x, x -> y
  }
  return result;
}

Mesh alongAxis(const Mesh& canonical, int upAxis) {
  if (upAxis == 1) return canonical;
  Mesh result;
  result.append(canonical, upAxisRotation(upAxis));
  return result;
}

// Flat-shaded triangle: its own three vertices with the face normal. Zero-area triangles are
// dropped because they have no normal.
void addFlatTriangle(Mesh& mesh, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 cross = (b - a).cross(c - a);
  const double length = cross.norm();
  if (!(length > 1e-300)) return;
  const Vec3 normal = cross / length;
  const std::uint32_t first = mesh.addVertex(a, normal);
  mesh.addVertex(b, normal);
  mesh.addVertex(c, normal);
  mesh.addTriangle(first, first + 1, first + 2);
}

// Hull of a point set with flat faces. Face orientation is checked against the hull's centroid
// rather than trusting the hull computer's edge order.
Mesh hullMesh(const std::vector<Vec3>& points) {
  Mesh mesh;
  if (points.size() < 4) return mesh;
  btConvexHullComputer hull;
  hull.compute(points.data()->data(), static_cast<int>(sizeof(Vec3)), static_cast<int>(points.size()),
               0.0, 0.0);
  if (hull.vertices.size() < 4) return mesh;
  Vec3 centroid = Vec3::Zero();
  for (int i = 0; i < hull.vertices.size(); ++i) centroid += toVec3(hull.vertices[i]);
  centroid /= hull.vertices.size();
  for (int f = 0; f < hull.faces.size(); ++f) {
    std::vector<Vec3> polygon;
    const btConvexHullComputer::Edge* start = &hull.edges[hull.faces[f]];
    const btConvexHullComputer::Edge* edge = start;
    do {
      polygon.push_back(toVec3(hull.vertices[edge->getTargetVertex()]));
      edge = edge->getNextEdgeOfFace();
    } while (edge != start && polygon.size() <= static_cast<std::size_t>(hull.vertices.size()));
    if (polygon.size() < 3) continue;
    // Newell's normal is robust for slightly non-planar polygons.
    Vec3 normal = Vec3::Zero(), center = Vec3::Zero();
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      normal += polygon[i].cross(polygon[(i + 1) % polygon.size()]);
      center += polygon[i];
    }
    center /= static_cast<double>(polygon.size());
    if (normal.dot(center - centroid) < 0.0) std::reverse(polygon.begin(), polygon.end());
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
      addFlatTriangle(mesh, polygon[0], polygon[i], polygon[i + 1]);
    }
  }
  return mesh;
}

// Any convex shape through its support mapping (margin included): the hull of its extreme points
// in directions spread evenly over the sphere (a Fibonacci lattice).
Mesh supportMappingMesh(const btConvexShape& shape, int segments) {
  const int directions = std::max(64, segments * segments / 2);
  std::vector<Vec3> points;
  points.reserve(static_cast<std::size_t>(directions));
  const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < directions; ++i) {
    const double y = 1.0 - 2.0 * (i + 0.5) / directions;
    const double r = std::sqrt(std::max(0.0, 1.0 - y * y));
    const double a = golden * i;
    const btVector3 direction(r * std::cos(a), y, r * std::sin(a));
    points.push_back(toVec3(shape.localGetSupportingVertex(direction)));
  }
  return hullMesh(points);
}

class TriangleCollector : public btTriangleCallback {
 public:
  explicit TriangleCollector(Mesh& mesh) : mesh_(mesh) {}
  void processTriangle(btVector3* triangle, int, int) override {
    addFlatTriangle(mesh_, toVec3(triangle[0]), toVec3(triangle[1]), toVec3(triangle[2]));
  }

 private:
  Mesh& mesh_;
};

Mesh planeMesh(const btStaticPlaneShape& plane, double halfExtent) {
  const Vec3 normal = toVec3(plane.getPlaneNormal()).normalized();
  btVector3 u, v;
  btPlaneSpace1(btVector3(normal.x(), normal.y(), normal.z()), u, v);
  Vec3 tu = toVec3(u).normalized(), tv = toVec3(v).normalized();
  if (tu.cross(tv).dot(normal) < 0.0) std::swap(tu, tv);
  const Vec3 center = normal * plane.getPlaneConstant();
  Mesh mesh;
  const std::uint32_t first = mesh.addVertex(center - halfExtent * (tu + tv), normal);
  mesh.addVertex(center + halfExtent * (tu - tv), normal);
  mesh.addVertex(center + halfExtent * (tu + tv), normal);
  mesh.addVertex(center - halfExtent * (tu - tv), normal);
  mesh.addTriangle(first, first + 1, first + 2);
  mesh.addTriangle(first, first + 2, first + 3);
  return mesh;
}

Mesh build(const btCollisionShape& shape, const ShapeMeshOptions& options, int depth) {
  // Compounds can nest; a cycle would be a corrupt shape, so bound the recursion.
  if (depth > 64) throw InvalidArgument("shape", "compound nested deeper than 64", "not supported");
  const int segments = options.curveSegments;
  switch (shape.getShapeType()) {
    case BOX_SHAPE_PROXYTYPE: {
      const auto& box = static_cast<const btBoxShape&>(shape);
      return makeBox(toVec3(box.getHalfExtentsWithMargin()));
    }
    case SPHERE_SHAPE_PROXYTYPE:
      return makeSphere(static_cast<const btSphereShape&>(shape).getRadius(), segments);
    case CAPSULE_SHAPE_PROXYTYPE: {
      const auto& capsule = static_cast<const btCapsuleShape&>(shape);
      return alongAxis(makeCapsule(capsule.getRadius(), capsule.getHalfHeight(), segments),
                       capsule.getUpAxis());
    }
    case CYLINDER_SHAPE_PROXYTYPE: {
      const auto& cylinder = static_cast<const btCylinderShape&>(shape);
      const int up = cylinder.getUpAxis();
      const btVector3 half = cylinder.getHalfExtentsWithMargin();
      return alongAxis(makeCylinder(cylinder.getRadius(), half[up], segments), up);
    }
    case CONE_SHAPE_PROXYTYPE: {
      const auto& cone = static_cast<const btConeShape&>(shape);
      return alongAxis(makeCone(cone.getRadius(), cone.getHeight(), segments), cone.getConeUpIndex());
    }
    case CONVEX_HULL_SHAPE_PROXYTYPE: {
      const auto& hull = static_cast<const btConvexHullShape&>(shape);
      std::vector<Vec3> points;
      for (int i = 0; i < hull.getNumPoints(); ++i) points.push_back(toVec3(hull.getScaledPoint(i)));
      return hullMesh(points);
    }
    case COMPOUND_SHAPE_PROXYTYPE: {
      const auto& compound = static_cast<const btCompoundShape&>(shape);
      Mesh mesh;
      for (int i = 0; i < compound.getNumChildShapes(); ++i) {
        mesh.append(build(*compound.getChildShape(i), options, depth + 1),
                    toIsometry(compound.getChildTransform(i)));
      }
      return mesh;
    }
    case STATIC_PLANE_PROXYTYPE:
      return planeMesh(static_cast<const btStaticPlaneShape&>(shape), options.planeHalfExtent);
    case EMPTY_SHAPE_PROXYTYPE:
      return Mesh{};
    default:
      break;
  }
  if (shape.isConcave()) {
    Mesh mesh;
    TriangleCollector collector(mesh);
    btVector3 aabbMin, aabbMax;
    shape.getAabb(btTransform::getIdentity(), aabbMin, aabbMax);
    const btVector3 pad(1.0, 1.0, 1.0);
    static_cast<const btConcaveShape&>(shape).processAllTriangles(&collector, aabbMin - pad, aabbMax + pad);
    return mesh;
  }
  if (shape.isConvex()) return supportMappingMesh(static_cast<const btConvexShape&>(shape), segments);
  throw InvalidArgument("shape", shape.getName(), "has no drawable surface");
}

}  // namespace

Mesh buildShapeMesh(const btCollisionShape& shape, const ShapeMeshOptions& options) {
  if (options.curveSegments < 3 || options.curveSegments > 1024) {
    throw InvalidArgument("options.curveSegments", std::to_string(options.curveSegments),
                          "must be within [3, 1024]");
  }
  requirePositive("options.planeHalfExtent", options.planeHalfExtent);
  return build(shape, options, 0);
}

bool isPlaneShape(const btCollisionShape& shape) { return shape.getShapeType() == STATIC_PLANE_PROXYTYPE; }

}  // namespace rope::render
