// SPDX-License-Identifier: MIT
#pragma once
// Plain triangle-mesh data: what scene extraction produces and the renderer uploads. Single
// precision because that is what the GPU consumes; positions in metres in the mesh's local frame.

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "render/bounding_box.h"
#include "render/colour.h"

namespace rope::render {

struct Vertex {
  std::array<float, 3> position{};
  std::array<float, 3> normal{};           // unit length, pointing out of the surface
  std::array<float, 3> colour{1, 1, 1};    // multiplied with the draw item's colour (sRGB, 0..1)
};

struct Mesh {
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> indices;  // triangle list, counter-clockwise seen from outside

  std::size_t triangleCount() const { return indices.size() / 3; }
  bool empty() const { return indices.empty(); }

  // Returns the new vertex's index.
  std::uint32_t addVertex(const Vec3& position, const Vec3& normal, const Rgb& colour = Rgb::Ones());
  void addTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c);
  // Appends other with its positions and normals moved by transform (a rigid motion).
  void append(const Mesh& other, const Eigen::Isometry3d& transform = Eigen::Isometry3d::Identity());
};

// Bounds of the mesh's vertices after transform; empty for an empty mesh.
BoundingBox meshBounds(const Mesh& mesh, const Eigen::Isometry3d& transform = Eigen::Isometry3d::Identity());

}  // namespace rope::render
