// SPDX-License-Identifier: MIT
#pragma once
// PNG files through libpng (8-bit RGB, no interlacing).

#include <string>

#include "render/image.h"

namespace rope::render {

// Throws InvalidArgument("image", ...) for an empty or inconsistent image and std::runtime_error
// naming the path when the file cannot be written.
void writePng(const std::string& path, const Image& image);

// Reads an 8-bit RGB or RGBA PNG (alpha dropped); throws std::runtime_error naming the path for a
// missing file or another format. For tests and tools that check what was written.
Image readPng(const std::string& path);

}  // namespace rope::render
