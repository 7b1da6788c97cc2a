// SPDX-License-Identifier: MIT
#include "render/world_extraction.h"

#include <btBulletCollisionCommon.h>

#include <array>
#include <string>

#include "rope/common/error.h"

namespace rope::render {

namespace {

Eigen::Isometry3d toIsometry(const btTransform& t) {
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  const btMatrix3x3& basis = t.getBasis();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) result.linear()(r, c) = basis[r][c];
  }
  result.translation() = Vec3(t.getOrigin().x(), t.getOrigin().y(), t.getOrigin().z());
  return result;
}

// Muted colours that read well under the renderer's warm key light.
constexpr std::array<std::array<float, 3>, 6> kPalette{{
    {0.36f, 0.55f, 0.78f},
    {0.84f, 0.38f, 0.33f},
    {0.45f, 0.70f, 0.45f},
    {0.93f, 0.74f, 0.30f},
    {0.62f, 0.46f, 0.75f},
    {0.35f, 0.72f, 0.72f},
}};

}  // namespace

Rgb defaultObjectColour(const btCollisionObject& object) {
  const btCollisionShape* shape = object.getCollisionShape();
  if (shape != nullptr && isPlaneShape(*shape)) return Rgb(0.80f, 0.80f, 0.78f);
  if (object.isStaticObject()) return Rgb(0.74f, 0.70f, 0.62f);  // stone: scenery, apart from the ground
  const int index = object.getWorldArrayIndex();
  const auto& c = kPalette[static_cast<std::size_t>(index < 0 ? 0 : index) % kPalette.size()];
  return Rgb(c[0], c[1], c[2]);
}

void extractObjects(const btCollisionObject* const* objects, int count, ShapeMeshCache& cache, Scene& scene,
                    const ExtractionOptions& options) {
  // Build into a scratch list first so that an exception leaves scene as it was.
  Scene added;
  for (int i = 0; i < count; ++i) {
    const btCollisionObject* object = objects[i];
    if (object == nullptr) throw InvalidArgument("objects[" + std::to_string(i) + "]", "null", "must not be null");
    if (options.skip && options.skip(*object)) continue;
    const btCollisionShape* shape = object->getCollisionShape();
    if (shape == nullptr) continue;
    auto mesh = cache.get(*shape);
    if (mesh->empty()) continue;
    const Rgb colour = options.colour ? options.colour(*object) : defaultObjectColour(*object);
    added.add(mesh, toIsometry(object->getWorldTransform()), colour,
              isPlaneShape(*shape) ? Material::Ground : Material::Surface);
  }
  scene.items.insert(scene.items.end(), added.items.begin(), added.items.end());
}

void extractWorld(const btCollisionWorld& world, ShapeMeshCache& cache, Scene& scene,
                  const ExtractionOptions& options) {
  const btCollisionObjectArray& array = world.getCollisionObjectArray();
  extractObjects(array.size() > 0 ? &array[0] : nullptr, array.size(), cache, scene, options);
}

}  // namespace rope::render
