// SPDX-License-Identifier: MIT
#include "demos/scene_file/obj_mesh.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rope::demos {

namespace {

// The vertex index of a face entry "a", "a/t", "a//n" or "a/t/n" (1-based, or negative: from the end).
int vertexIndex(const std::string& entry, int vertexCount, int line) {
  const std::string number = entry.substr(0, entry.find('/'));
  std::size_t used = 0;
  long index = 0;
  try {
    index = std::stol(number, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != number.size() || index == 0) {
    throw std::runtime_error("line " + std::to_string(line) + ": bad face index '" + entry + "'");
  }
  const long resolved = index > 0 ? index - 1 : vertexCount + index;
  if (resolved < 0 || resolved >= vertexCount) {
    throw std::runtime_error("line " + std::to_string(line) + ": face index " + std::to_string(index) +
                             " with " + std::to_string(vertexCount) + " vertices so far");
  }
  return static_cast<int>(resolved);
}

}  // namespace

ObjMesh readObjMesh(const std::string& file) {
  std::ifstream stream(file);
  if (!stream) throw std::runtime_error("not found");
  ObjMesh mesh;
  int lineNumber = 0;
  for (std::string line; std::getline(stream, line);) {
    ++lineNumber;
    std::istringstream words(line);
    std::string kind;
    words >> kind;
    if (kind == "v") {
      double x = 0.0, y = 0.0, z = 0.0;
      if (!(words >> x >> y >> z) || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
        throw std::runtime_error("line " + std::to_string(lineNumber) + ": a vertex needs three finite numbers");
      }
      mesh.vertices.emplace_back(x, y, z);
    } else if (kind == "f") {
      std::vector<int> face;
      for (std::string entry; words >> entry;) {
        face.push_back(vertexIndex(entry, static_cast<int>(mesh.vertices.size()), lineNumber));
      }
      if (face.size() < 3) throw std::runtime_error("line " + std::to_string(lineNumber) + ": a face needs three vertices");
      for (std::size_t i = 1; i + 1 < face.size(); ++i) mesh.triangles.push_back({face[0], face[i], face[i + 1]});
    }
  }
  if (mesh.triangles.empty()) throw std::runtime_error("has no triangles");
  return mesh;
}

}  // namespace rope::demos
