// SPDX-License-Identifier: MIT
#include "render/colour.h"

#include <cmath>
#include <string>

#include "rope/common/error.h"

namespace rope::render {

void requireColour(const char* parameter, const Rgb& colour) {
  for (int i = 0; i < 3; ++i) {
    const double c = colour[i];
    const std::string name = std::string(parameter) + "[" + std::to_string(i) + "]";
    requireFinite(name, c);
    if (c < 0.0 || c > 1.0) throw InvalidArgument(name, formatValue(c), "must be within [0, 1]");
  }
}

}  // namespace rope::render
