// SPDX-License-Identifier: MIT
#pragma once
// Triangle meshes of Bullet collision shapes, in the shape's local frame with its local scaling
// applied: box, sphere, capsule, cylinder and cone (any up axis), convex hulls and every other
// convex shape (through its support mapping), compounds (children placed by their local
// transforms), static planes (a large finite quad) and concave shapes such as triangle meshes and
// heightfields (through processAllTriangles).

#include "render/mesh.h"

class btCollisionShape;

namespace rope::render {

struct ShapeMeshOptions {
  int curveSegments = 32;         // points around round outlines, 3..1024
  double planeHalfExtent = 50.0;  // metres, > 0: half size of the quad standing in for a plane
};

// Throws InvalidArgument("options.curveSegments"/"options.planeHalfExtent", ...) for bad options and
// InvalidArgument("shape", <Bullet shape name>) for a shape type with no surface (e.g. a
// btEmptyShape yields an empty mesh instead; soft bodies are not collision shapes).
Mesh buildShapeMesh(const btCollisionShape& shape, const ShapeMeshOptions& options = {});

// True for btStaticPlaneShape, which the renderer draws as ground with a grid.
bool isPlaneShape(const btCollisionShape& shape);

}  // namespace rope::render
