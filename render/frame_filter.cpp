// SPDX-License-Identifier: MIT
#include "render/frame_filter.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "rope/common/error.h"

namespace rope::render {

namespace {

// Integer luma in [0, 255] (Rec. 601 weights), which is all the edge test needs.
inline int lumaOf(const std::uint8_t* p) { return (77 * p[0] + 150 * p[1] + 29 * p[2]) >> 8; }

struct Source {
  const std::uint8_t* rgba;
  int width, height;
  // Pixel (x, y) in image coordinates (y down) of the bottom-up buffer.
  const std::uint8_t* at(int x, int y) const {
    x = std::clamp(x, 0, width - 1);
    y = std::clamp(y, 0, height - 1);
    return rgba + (static_cast<std::size_t>(height - 1 - y) * static_cast<std::size_t>(width) + x) * 4;
  }
  // Bilinear sample at pixel-centre coordinates (x + 0.5 is a pixel centre).
  void sample(float fx, float fy, float out[3]) const {
    fx -= 0.5f;
    fy -= 0.5f;
    const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
    const float ax = fx - static_cast<float>(x0), ay = fy - static_cast<float>(y0);
    const std::uint8_t* p00 = at(x0, y0);
    const std::uint8_t* p10 = at(x0 + 1, y0);
    const std::uint8_t* p01 = at(x0, y0 + 1);
    const std::uint8_t* p11 = at(x0 + 1, y0 + 1);
    for (int c = 0; c < 3; ++c) {
      const float top = p00[c] + ax * static_cast<float>(p10[c] - p00[c]);
      const float bottom = p01[c] + ax * static_cast<float>(p11[c] - p01[c]);
      out[c] = top + ay * (bottom - top);
    }
  }
};

void copyRow(const Source& source, int y, std::uint8_t* target) {
  const std::uint8_t* row = source.at(0, y);
  for (int x = 0; x < source.width; ++x) {
    target[3 * x] = row[4 * x];
    target[3 * x + 1] = row[4 * x + 1];
    target[3 * x + 2] = row[4 * x + 2];
  }
}

// Filters an interior pixel whose 3x3 neighbourhood holds geometry; target already holds the
// pixel's own colour and is overwritten only where an edge is found.
void filterPixel(const Source& source, int x, int y, std::uint8_t* target) {
  const std::uint8_t* centre = source.at(x, y);
  const std::size_t stride = static_cast<std::size_t>(source.width) * 4;
  // Rows are bottom-up in memory: image row y - 1 (north) is one stride further on.
  const std::uint8_t* nw = centre + stride - 4;
  const std::uint8_t* ne = centre + stride + 4;
  const std::uint8_t* sw = centre - stride - 4;
  const std::uint8_t* se = centre - stride + 4;
  const int lc = lumaOf(centre), lnw = lumaOf(nw), lne = lumaOf(ne), lsw = lumaOf(sw), lse = lumaOf(se);
  const int lo = std::min({lc, lnw, lne, lsw, lse});
  const int hi = std::max({lc, lnw, lne, lsw, lse});
  // Low contrast (relative to brightness, so dark regions are not smeared): keep the pixel.
  if (hi - lo < std::max(8, hi / 8)) return;
  // Luma gradient across the edge (y down), turned by 90 degrees: the direction along the edge.
  float dx = static_cast<float>((lnw + lne) - (lsw + lse));
  float dy = static_cast<float>((lne + lse) - (lnw + lsw));
  const float damping = std::max(static_cast<float>(lnw + lne + lsw + lse) / 32.0f, 2.0f);
  const float scale = 1.0f / (std::min(std::abs(dx), std::abs(dy)) + damping);
  dx = std::clamp(dx * scale, -6.0f, 6.0f);
  dy = std::clamp(dy * scale, -6.0f, 6.0f);
  const float cx = static_cast<float>(x) + 0.5f, cy = static_cast<float>(y) + 0.5f;
  float a[3], b[3], c[3], d[3];
  source.sample(cx - dx / 6.0f, cy - dy / 6.0f, a);
  source.sample(cx + dx / 6.0f, cy + dy / 6.0f, b);
  source.sample(cx - dx * 0.5f, cy - dy * 0.5f, c);
  source.sample(cx + dx * 0.5f, cy + dy * 0.5f, d);
  float inner[3], outer[3];
  for (int k = 0; k < 3; ++k) {
    inner[k] = 0.5f * (a[k] + b[k]);
    outer[k] = 0.5f * inner[k] + 0.25f * (c[k] + d[k]);
  }
  const float lOuter = (77.0f * outer[0] + 150.0f * outer[1] + 29.0f * outer[2]) / 256.0f;
  // The wide blend can reach across a second edge; the narrow one is used then.
  const float* chosen = (lOuter < static_cast<float>(lo - 1) || lOuter > static_cast<float>(hi + 1)) ? inner : outer;
  for (int k = 0; k < 3; ++k) target[k] = static_cast<std::uint8_t>(std::clamp(chosen[k] + 0.5f, 0.0f, 255.0f));
}

}  // namespace

void convertFrame(const std::uint8_t* rgba, int width, int height, bool antiAlias, Image& out) {
  if (rgba == nullptr) throw InvalidArgument("rgba", "null", "must point to width*height*4 bytes");
  if (out.width != width || out.height != height) out = Image(width, height);  // validates the size
  const Source source{rgba, width, height};
  if (!antiAlias || width < 3 || height < 3) {
    for (int y = 0; y < height; ++y) copyRow(source, y, out.pixel(0, y));
    return;
  }
  copyRow(source, 0, out.pixel(0, 0));
  copyRow(source, height - 1, out.pixel(0, height - 1));
  auto filterRows = [&source, &out, width](int begin, int end) {
    // Alpha of each column ORed over the rows y - 1, y, y + 1: simple loops the compiler
    // vectorises, so that the common case (no geometry nearby) costs a copy and a few byte tests.
    std::vector<std::uint8_t> vertical(static_cast<std::size_t>(width));
    for (int y = begin; y < end; ++y) {
      std::uint8_t* target = out.pixel(0, y);
      copyRow(source, y, target);
      const std::uint8_t* above = source.at(0, y - 1);
      const std::uint8_t* row = source.at(0, y);
      const std::uint8_t* below = source.at(0, y + 1);
      for (int x = 0; x < width; ++x) {
        vertical[static_cast<std::size_t>(x)] = above[4 * x + 3] | row[4 * x + 3] | below[4 * x + 3];
      }
      for (int x = 1; x + 1 < width; ++x) {
        const std::size_t i = static_cast<std::size_t>(x);
        if ((vertical[i - 1] | vertical[i] | vertical[i + 1]) != 0) filterPixel(source, x, y, target + 3 * x);
      }
    }
  };
  // Large frames are split between this thread and one helper: the GL worker threads are idle
  // while the frame is converted, and the filter reads the immutable source only.
  const int middle = height / 2;
  if (static_cast<long>(width) * height >= 200000) {
    std::thread helper(filterRows, middle, height - 1);
    filterRows(1, middle);
    helper.join();
  } else {
    filterRows(1, height - 1);
  }
}

}  // namespace rope::render
