// SPDX-License-Identifier: MIT
#pragma once
// Wavefront OBJ meshes for scene-file bodies (`"shape": "mesh"`): the vertices ("v x y z") and faces
// ("f a b c ...", fanned into triangles; indices 1-based or negative, "a/t/n" forms accepted) of a
// file; every other line (normals, texture coordinates, groups, materials) is ignored.

#include <array>
#include <string>
#include <vector>

#include "rope/common/types.h"

namespace rope::demos {

struct ObjMesh {
  PointList vertices;                       // m (as the file writes them)
  std::vector<std::array<int, 3>> triangles;  // 0-based vertex indices
};

// Throws std::runtime_error: "not found" for a file that cannot be opened, "line N: ..." for a
// malformed line or an index out of range, "has no triangles" for a file without faces.
ObjMesh readObjMesh(const std::string& file);

}  // namespace rope::demos
