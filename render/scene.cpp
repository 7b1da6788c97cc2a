// SPDX-License-Identifier: MIT
#include "render/scene.h"

#include "rope/common/error.h"

namespace rope::render {

void Scene::add(std::shared_ptr<const Mesh> mesh, const Eigen::Isometry3d& transform, const Rgb& colour,
                Material material) {
  if (!mesh) throw InvalidArgument("mesh", "null", "must point to a mesh");
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) requireFinite("transform", transform.matrix()(r, c));
  }
  requireColour("colour", colour);
  items.push_back(DrawItem{std::move(mesh), transform, colour, material});
}

BoundingBox Scene::bounds() const {
  BoundingBox box;
  for (const DrawItem& item : items) {
    if (item.material != Material::Ground) box.extend(meshBounds(*item.mesh, item.transform));
  }
  return box;
}

bool Scene::hasGround() const {
  for (const DrawItem& item : items) {
    if (item.material == Material::Ground) return true;
  }
  return false;
}

}  // namespace rope::render
