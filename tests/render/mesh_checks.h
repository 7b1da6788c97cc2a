// SPDX-License-Identifier: MIT
#pragma once
// Shared assertions on triangle meshes for the extraction tests.

#include <gtest/gtest.h>

#include <map>
#include <tuple>

#include "render/mesh.h"

namespace rope::render::test {

inline Vec3 position(const Vertex& v) { return Vec3(v.position[0], v.position[1], v.position[2]); }
inline Vec3 normal(const Vertex& v) { return Vec3(v.normal[0], v.normal[1], v.normal[2]); }

// Indices in range, normals of unit length.
inline void expectWellFormed(const Mesh& mesh) {
  ASSERT_EQ(mesh.indices.size() % 3, 0u);
  for (std::uint32_t i : mesh.indices) ASSERT_LT(i, mesh.vertices.size());
  for (const Vertex& v : mesh.vertices) ASSERT_NEAR(normal(v).norm(), 1.0, 1e-5);
}

// Closed surface: every edge, matched by vertex positions (flat-shaded meshes duplicate vertices),
// is used exactly twice, once in each direction (consistent orientation).
inline void expectClosed(const Mesh& mesh, double quantum = 1e-5) {
  using Key = std::tuple<long, long, long>;
  auto key = [quantum](const Vertex& v) {
    return Key(std::lround(v.position[0] / quantum), std::lround(v.position[1] / quantum),
               std::lround(v.position[2] / quantum));
  };
  std::map<std::pair<Key, Key>, int> directed;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    for (int e = 0; e < 3; ++e) {
      const Key a = key(mesh.vertices[mesh.indices[t + e]]);
      const Key b = key(mesh.vertices[mesh.indices[t + (e + 1) % 3]]);
      if (a == b) continue;
      ++directed[{a, b}];
    }
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << "edge used twice in the same direction";
    const auto reverse = directed.find({edge.second, edge.first});
    EXPECT_TRUE(reverse != directed.end() && reverse->second == 1) << "open or inconsistently oriented edge";
  }
}

// For a convex mesh around centre: every triangle's geometric normal (from its winding) points
// away from the centre, and agrees with its vertex normals.
inline void expectOutward(const Mesh& mesh, const Vec3& centre) {
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const Vec3 a = position(mesh.vertices[mesh.indices[t]]);
    const Vec3 b = position(mesh.vertices[mesh.indices[t + 1]]);
    const Vec3 c = position(mesh.vertices[mesh.indices[t + 2]]);
    const Vec3 n = (b - a).cross(c - a);
    if (n.norm() < 1e-12) continue;
    EXPECT_GT(n.dot((a + b + c) / 3.0 - centre), 0.0) << "triangle " << t / 3 << " faces inward";
    for (int k = 0; k < 3; ++k) {
      EXPECT_GT(n.normalized().dot(normal(mesh.vertices[mesh.indices[t + k]])), 0.0)
          << "vertex normal against the winding in triangle " << t / 3;
    }
  }
}

// Signed volume by the divergence theorem (positive for an outward-oriented closed mesh).
inline double enclosedVolume(const Mesh& mesh) {
  double volume = 0.0;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const Vec3 a = position(mesh.vertices[mesh.indices[t]]);
    const Vec3 b = position(mesh.vertices[mesh.indices[t + 1]]);
    const Vec3 c = position(mesh.vertices[mesh.indices[t + 2]]);
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

}  // namespace rope::render::test
