// SPDX-License-Identifier: MIT
#include "render/image.h"

#include <algorithm>
#include <string>

#include "rope/common/error.h"

namespace rope::render {

namespace {
void requireSize(const char* parameter, int value) {
  if (value < 1 || value > 16384) throw InvalidArgument(parameter, std::to_string(value), "must be within [1, 16384]");
}
}  // namespace

Image::Image(int w, int h) {
  requireSize("width", w);
  requireSize("height", h);
  width = w;
  height = h;
  pixels.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3, 0);
}

void flipVertically(Image& image) {
  const std::size_t row = static_cast<std::size_t>(image.width) * 3;
  for (int y = 0; y < image.height / 2; ++y) {
    std::swap_ranges(image.pixels.begin() + static_cast<std::ptrdiff_t>(y * row),
                     image.pixels.begin() + static_cast<std::ptrdiff_t>((y + 1) * row),
                     image.pixels.begin() + static_cast<std::ptrdiff_t>((image.height - 1 - y) * row));
  }
}

}  // namespace rope::render
