// SPDX-License-Identifier: MIT
#include "render/shape_mesh_cache.h"

#include <btBulletCollisionCommon.h>

namespace rope::render {

ShapeMeshCache::ShapeMeshCache(const ShapeMeshOptions& options) : options_(options) {
  // Validate now rather than on the first get().
  btEmptyShape empty;
  buildShapeMesh(empty, options_);
}

std::shared_ptr<const Mesh> ShapeMeshCache::get(const btCollisionShape& shape) {
  btVector3 aabbMin, aabbMax;
  shape.getAabb(btTransform::getIdentity(), aabbMin, aabbMax);
  const btVector3& scaling = shape.getLocalScaling();
  const Fingerprint fingerprint{static_cast<double>(shape.getShapeType()),
                                scaling.x(), scaling.y(), scaling.z(), shape.getMargin(),
                                aabbMin.x(), aabbMin.y(), aabbMin.z(), aabbMax.x(), aabbMax.y(), aabbMax.z()};
  auto found = entries_.find(&shape);
  if (found != entries_.end() && found->second.fingerprint == fingerprint) return found->second.mesh;
  auto mesh = std::make_shared<const Mesh>(buildShapeMesh(shape, options_));
  ++builds_;
  entries_[&shape] = Entry{fingerprint, mesh};
  return mesh;
}

}  // namespace rope::render
