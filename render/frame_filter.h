// SPDX-License-Identifier: MIT
#pragma once
// Turns a frame read back from OpenGL (RGBA8, rows bottom-up) into an Image (RGB8, rows top-down),
// optionally anti-aliasing it on the way. The anti-aliasing is edge-directed post-filtering in the
// spirit of FXAA: where the luma contrast among a pixel's diagonal neighbours is high, the edge
// direction is estimated from them and the pixel is blended with bilinear samples along the edge.
// Only pixels whose 3x3 neighbourhood has a non-zero alpha are considered: the renderer writes
// alpha 0 for surfaces that anti-alias themselves (sky, ground grid), so the filter spends its time
// on object silhouettes only. Done on the CPU because llvmpipe's texture sampling makes the same
// pass several times more expensive as a shader, and it rides along with the copy that the
// read-back needs anyway.

#include <cstdint>

#include "render/image.h"

namespace rope::render {

// rgba: width * height * 4 bytes, bottom row first. out is resized to width x height.
// Throws InvalidArgument for a null "rgba" or a size outside [1, 16384].
void convertFrame(const std::uint8_t* rgba, int width, int height, bool antiAlias, Image& out);

}  // namespace rope::render
