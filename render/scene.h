// SPDX-License-Identifier: MIT
#pragma once
// The extracted draw list: everything the renderer needs for one frame, as plain data with no GL
// and no Bullet. Meshes are shared and immutable once added; the renderer keeps their GPU copies
// keyed by identity, so a mesh reused across frames (a static shape) is uploaded only once.

#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "render/mesh.h"

namespace rope::render {

enum class Material {
  Surface,  // lit, shadowed, casts shadows
  Ground,   // flat mesh (one normal, read from its first vertex): lit, shadowed, with the ground grid
            // drawn on it; casts no shadow
  Overlay,  // annotation (control polygon): lightly shaded, no shadows, visible through surfaces
};

struct DrawItem {
  std::shared_ptr<const Mesh> mesh;
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();  // mesh frame -> world
  Rgb colour{1, 1, 1};                                          // multiplies the vertex colours
  Material material = Material::Surface;
};

struct Scene {
  std::vector<DrawItem> items;

  // Throws InvalidArgument for a null "mesh", a non-finite "transform" or a bad "colour".
  void add(std::shared_ptr<const Mesh> mesh, const Eigen::Isometry3d& transform = Eigen::Isometry3d::Identity(),
           const Rgb& colour = Rgb::Ones(), Material material = Material::Surface);
  void clear() { items.clear(); }

  // World bounds of the items, ground excluded (planes are huge and would swamp the framing).
  BoundingBox bounds() const;
  bool hasGround() const;
};

}  // namespace rope::render
