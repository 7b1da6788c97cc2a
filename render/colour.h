// SPDX-License-Identifier: MIT
#pragma once
// Colours are sRGB-encoded RGB triples in [0, 1] (what a colour picker shows); the renderer converts
// them to linear light for shading and back for the output image.

#include <Eigen/Core>

namespace rope::render {

using Rgb = Eigen::Vector3f;

// Throws InvalidArgument(parameter, value) unless every channel is finite and within [0, 1].
void requireColour(const char* parameter, const Rgb& colour);

}  // namespace rope::render
