// SPDX-License-Identifier: MIT
#pragma once
// The floor of the demo scenes: the plane y = height, drawn with the renderer's ground grid.

#include "render/scene.h"

namespace rope::demos {

void addGround(render::Scene& scene, double height = 0.0);

}  // namespace rope::demos
