// SPDX-License-Identifier: MIT
#pragma once
// Closed triangle meshes of the primitive solids, centred on the origin with their axis along +Y
// (Bullet's default up axis). Lengths in metres. Curved surfaces carry smooth normals, flat faces
// their own vertices with the face normal, so edges stay crisp under lighting.

#include "render/mesh.h"

namespace rope::render {

// Every builder throws InvalidArgument naming the parameter for a non-finite or non-positive size
// or a resolution outside its range.

// Half extents along x, y, z: 24 vertices, 12 triangles.
Mesh makeBox(const Vec3& halfExtents);
// segments: points around the equator, 3..1024; segments/2 (at least 2) latitude bands.
Mesh makeSphere(double radius, int segments);
// Cylinder of total length 2*halfHeight between two spherical caps.
Mesh makeCapsule(double radius, double halfHeight, int segments);
// sides: 3..1024. Caps are optional so the control-polygon overlay can use open tubes.
Mesh makeCylinder(double radius, double halfHeight, int sides, bool caps = true);
// Apex at +height/2, base disc at -height/2 (as btConeShape).
Mesh makeCone(double radius, double height, int sides);

}  // namespace rope::render
