// SPDX-License-Identifier: MIT
#pragma once
// An 8-bit RGB image, rows stored top to bottom (as PNG and video expect; OpenGL reads rows bottom
// up, which the renderer flips).

#include <cstdint>
#include <vector>

namespace rope::render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 3 bytes, row-major, top row first

  Image() = default;
  // Black image; throws InvalidArgument for "width"/"height" outside [1, 16384].
  Image(int width, int height);

  bool empty() const { return pixels.empty(); }
  const std::uint8_t* pixel(int x, int y) const { return &pixels[(static_cast<std::size_t>(y) * width + x) * 3]; }
  std::uint8_t* pixel(int x, int y) { return &pixels[(static_cast<std::size_t>(y) * width + x) * 3]; }
};

// Reverses the row order in place.
void flipVertically(Image& image);

}  // namespace rope::render
