// SPDX-License-Identifier: MIT
#pragma once
// Scene extraction from Bullet: one draw item per collision object, meshed from its collision shape
// and placed by its world transform. Works without a GL context, so it is unit-testable.

#include <functional>
#include <vector>

#include "render/scene.h"
#include "render/shape_mesh_cache.h"

class btCollisionObject;
class btCollisionWorld;

namespace rope::render {

struct ExtractionOptions {
  // Objects for which this returns true are left out, e.g. the capsules standing in for a rope's
  // collision geometry (the rope itself is drawn from its spline). Empty: nothing is skipped.
  std::function<bool(const btCollisionObject&)> skip;
  // Colour of an object (sRGB, channels in [0, 1]). Empty: planes are light grey, other static
  // objects stone-coloured, and the rest take a colour from a fixed palette by their index in the
  // world.
  std::function<Rgb(const btCollisionObject&)> colour;
};

// Appends the objects of world to scene (scene is not cleared). Planes become Material::Ground.
void extractWorld(const btCollisionWorld& world, ShapeMeshCache& cache, Scene& scene,
                  const ExtractionOptions& options = {});

// The same for an explicit list (null entries throw InvalidArgument("objects[i]", "null")).
void extractObjects(const btCollisionObject* const* objects, int count, ShapeMeshCache& cache, Scene& scene,
                    const ExtractionOptions& options = {});

inline void extractObjects(const std::vector<const btCollisionObject*>& objects, ShapeMeshCache& cache, Scene& scene,
                           const ExtractionOptions& options = {}) {
  extractObjects(objects.data(), static_cast<int>(objects.size()), cache, scene, options);
}

// The default colour rule described above.
Rgb defaultObjectColour(const btCollisionObject& object);

}  // namespace rope::render
