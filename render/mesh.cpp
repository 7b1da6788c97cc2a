// SPDX-License-Identifier: MIT
#include "render/mesh.h"

#include <limits>
#include <stdexcept>

namespace rope::render {

namespace {
std::array<float, 3> toFloat(const Vec3& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}
Vec3 asVec3(const std::array<float, 3>& v) { return Vec3(v[0], v[1], v[2]); }
}  // namespace

std::uint32_t Mesh::addVertex(const Vec3& position, const Vec3& normal, const Rgb& colour) {
  // 32-bit indices are what the renderer draws with; a mesh that large is a caller error anyway.
  if (vertices.size() >= std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error("rope::render::Mesh: more than 2^32-1 vertices");
  }
  vertices.push_back(Vertex{toFloat(position), toFloat(normal), {colour.x(), colour.y(), colour.z()}});
  return static_cast<std::uint32_t>(vertices.size() - 1);
}

void Mesh::addTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  indices.push_back(a);
  indices.push_back(b);
  indices.push_back(c);
}

void Mesh::append(const Mesh& other, const Eigen::Isometry3d& transform) {
  const auto offset = static_cast<std::uint32_t>(vertices.size());
  vertices.reserve(vertices.size() + other.vertices.size());
  const Eigen::Matrix3d rotation = transform.linear();
  for (const Vertex& v : other.vertices) {
    Vertex moved = v;
    moved.position = toFloat(transform * asVec3(v.position));
    moved.normal = toFloat(rotation * asVec3(v.normal));
    vertices.push_back(moved);
  }
  indices.reserve(indices.size() + other.indices.size());
  for (std::uint32_t i : other.indices) indices.push_back(i + offset);
}

BoundingBox meshBounds(const Mesh& mesh, const Eigen::Isometry3d& transform) {
  BoundingBox box;
  for (const Vertex& v : mesh.vertices) box.extend(transform * asVec3(v.position));
  return box;
}

}  // namespace rope::render
