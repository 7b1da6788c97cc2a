// SPDX-License-Identifier: MIT
#include "render/primitive_mesh.h"

#include <cmath>
#include <string>

#include "rope/common/error.h"

namespace rope::render {

namespace {

constexpr double kPi = 3.14159265358979323846;

void requireResolution(const char* parameter, int value, int minimum) {
  if (value < minimum || value > 1024) {
    throw InvalidArgument(parameter, std::to_string(value),
                          "must be within [" + std::to_string(minimum) + ", 1024]");
  }
}

// Latitude band rows of a sphere split at the equator; the two hemispheres are shifted apart by
// ±halfHeight along Y, which turns the same code into a capsule (halfHeight = 0: a sphere).
Mesh makeRoundedCylinder(double radius, double halfHeight, int segments) {
  Mesh mesh;
  const int halfBands = std::max(1, segments / 4);  // bands per hemisphere
  // Rows from the north pole (row 0) to the south pole (row 2*halfBands+1); the equator is
  // duplicated (rows halfBands and halfBands+1) with the two hemisphere offsets.
  const int rows = 2 * halfBands + 2;
  for (int row = 0; row < rows; ++row) {
    const bool north = row <= halfBands;
    const int band = north ? row : row - 1;  // 0..2*halfBands
    const double polar = kPi * band / (2 * halfBands);
    const double y = std::cos(polar), ring = std::sin(polar);
    const double offset = north ? halfHeight : -halfHeight;
    for (int j = 0; j < segments; ++j) {
      const double azimuth = 2.0 * kPi * j / segments;
      const Vec3 normal(ring * std::cos(azimuth), y, -ring * std::sin(azimuth));
      mesh.addVertex(radius * normal + Vec3(0, offset, 0), normal);
    }
  }
  for (int row = 0; row + 1 < rows; ++row) {
    if (halfHeight == 0.0 && row == halfBands) continue;  // zero-height equator strip
    for (int j = 0; j < segments; ++j) {
      const auto a = static_cast<std::uint32_t>(row * segments + j);
      const auto b = static_cast<std::uint32_t>(row * segments + (j + 1) % segments);
      const auto c = static_cast<std::uint32_t>((row + 1) * segments + j);
      const auto d = static_cast<std::uint32_t>((row + 1) * segments + (j + 1) % segments);
      // Rows at the poles collapse to a point: skip the zero-area half of their quads.
      if (row != 0) mesh.addTriangle(a, c, b);
      if (row + 2 != rows) mesh.addTriangle(b, c, d);
    }
  }
  return mesh;
}

void addDisc(Mesh& mesh, double radius, double y, bool up, int sides) {
  const Vec3 normal(0, up ? 1 : -1, 0);
  const std::uint32_t center = mesh.addVertex(Vec3(0, y, 0), normal);
  for (int j = 0; j < sides; ++j) {
    const double a = 2.0 * kPi * j / sides;
    mesh.addVertex(Vec3(radius * std::cos(a), y, -radius * std::sin(a)), normal);
  }
  for (int j = 0; j < sides; ++j) {
    const std::uint32_t p = center + 1 + static_cast<std::uint32_t>(j);
    const std::uint32_t q = center + 1 + static_cast<std::uint32_t>((j + 1) % sides);
    if (up) {
      mesh.addTriangle(center, p, q);
    } else {
      mesh.addTriangle(center, q, p);
    }
  }
}

}  // namespace

Mesh makeBox(const Vec3& halfExtents) {
  requirePositive("halfExtents.x", halfExtents.x());
  requirePositive("halfExtents.y", halfExtents.y());
  requirePositive("halfExtents.z", halfExtents.z());
  Mesh mesh;
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign = -1; sign <= 1; sign += 2) {
      Vec3 normal = Vec3::Zero();
      normal[axis] = sign;
      // u, v span the face so that u x v = normal (counter-clockwise seen from outside).
      Vec3 u = Vec3::Zero(), v = Vec3::Zero();
      u[(axis + 1) % 3] = 1.0;
      v[(axis + 2) % 3] = 1.0;
      if (sign < 0) std::swap(u, v);
      const Vec3 c = normal.cwiseProduct(halfExtents);
      const Vec3 du = u.cwiseProduct(halfExtents), dv = v.cwiseProduct(halfExtents);
      const std::uint32_t first = mesh.addVertex(c - du - dv, normal);
      mesh.addVertex(c + du - dv, normal);
      mesh.addVertex(c + du + dv, normal);
      mesh.addVertex(c - du + dv, normal);
      mesh.addTriangle(first, first + 1, first + 2);
      mesh.addTriangle(first, first + 2, first + 3);
    }
  }
  return mesh;
}

Mesh makeSphere(double radius, int segments) {
  requirePositive("radius", radius);
  requireResolution("segments", segments, 3);
  return makeRoundedCylinder(radius, 0.0, segments);
}

Mesh makeCapsule(double radius, double halfHeight, int segments) {
  requirePositive("radius", radius);
  requireNonNegative("halfHeight", halfHeight);
  requireResolution("segments", segments, 3);
  return makeRoundedCylinder(radius, halfHeight, segments);
}

Mesh makeCylinder(double radius, double halfHeight, int sides, bool caps) {
  requirePositive("radius", radius);
  requirePositive("halfHeight", halfHeight);
  requireResolution("sides", sides, 3);
  Mesh mesh;
  for (int j = 0; j < sides; ++j) {
    const double a = 2.0 * kPi * j / sides;
    const Vec3 normal(std::cos(a), 0, -std::sin(a));
    mesh.addVertex(radius * normal + Vec3(0, halfHeight, 0), normal);
    mesh.addVertex(radius * normal - Vec3(0, halfHeight, 0), normal);
  }
  for (int j = 0; j < sides; ++j) {
    const auto top = static_cast<std::uint32_t>(2 * j), bottom = top + 1;
    const auto nextTop = static_cast<std::uint32_t>(2 * ((j + 1) % sides)), nextBottom = nextTop + 1;
    mesh.addTriangle(top, bottom, nextTop);
    mesh.addTriangle(nextTop, bottom, nextBottom);
  }
  if (caps) {
    addDisc(mesh, radius, halfHeight, true, sides);
    addDisc(mesh, radius, -halfHeight, false, sides);
  }
  return mesh;
}

Mesh makeCone(double radius, double height, int sides) {
  requirePositive("radius", radius);
  requirePositive("height", height);
  requireResolution("sides", sides, 3);
  Mesh mesh;
  const double half = 0.5 * height;
  // Smooth normal of the lateral surface: perpendicular to the slant line.
  const double slant = std::hypot(radius, height);
  const double ny = radius / slant, nr = height / slant;
  for (int j = 0; j < sides; ++j) {
    const double a = 2.0 * kPi * j / sides;
    const double am = 2.0 * kPi * (j + 0.5) / sides;
    const Vec3 normal(nr * std::cos(a), ny, -nr * std::sin(a));
    // Each side gets its own apex vertex with the normal of the side's middle, which avoids the
    // black pinch a single shared apex normal produces.
    mesh.addVertex(Vec3(0, half, 0), Vec3(nr * std::cos(am), ny, -nr * std::sin(am)));
    mesh.addVertex(Vec3(radius * std::cos(a), -half, -radius * std::sin(a)), normal);
  }
  for (int j = 0; j < sides; ++j) {
    const auto apex = static_cast<std::uint32_t>(2 * j), base = apex + 1;
    const auto nextBase = static_cast<std::uint32_t>(2 * ((j + 1) % sides) + 1);
    mesh.addTriangle(apex, base, nextBase);
  }
  addDisc(mesh, radius, -half, false, sides);
  return mesh;
}

}  // namespace rope::render
