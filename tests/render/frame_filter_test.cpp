// SPDX-License-Identifier: MIT
#include "render/frame_filter.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "rope/common/error.h"

namespace rope::render {
namespace {

// RGBA buffer, bottom row first, filled by f(x, yImage) -> {r, g, b, a}.
template <typename F>
std::vector<std::uint8_t> frame(int w, int h, F f) {
  std::vector<std::uint8_t> rgba(static_cast<std::size_t>(w * h * 4));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const auto c = f(x, y);
      std::uint8_t* p = &rgba[static_cast<std::size_t>(((h - 1 - y) * w + x) * 4)];
      for (int k = 0; k < 4; ++k) p[k] = c[k];
    }
  }
  return rgba;
}

using Rgba = std::array<std::uint8_t, 4>;

TEST(FrameFilter, FlipsRowsAndDropsAlpha) {
  const auto rgba = frame(3, 2, [](int x, int y) { return Rgba{static_cast<std::uint8_t>(x), static_cast<std::uint8_t>(y), 7, 255}; });
  Image out;
  convertFrame(rgba.data(), 3, 2, false, out);
  ASSERT_EQ(out.width, 3);
  ASSERT_EQ(out.height, 2);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 3; ++x) {
      EXPECT_EQ(out.pixel(x, y)[0], x);
      EXPECT_EQ(out.pixel(x, y)[1], y);
      EXPECT_EQ(out.pixel(x, y)[2], 7);
    }
  }
}

// A jagged (staircase) diagonal edge between black and white object pixels.
Rgba staircase(int x, int y, std::uint8_t alpha) {
  const bool white = x > y / 2 + 4;
  const std::uint8_t v = white ? 255 : 0;
  return Rgba{v, v, v, alpha};
}

TEST(FrameFilter, SoftensGeometryEdgesAndKeepsFlatAreas) {
  const int w = 24, h = 24;
  const auto rgba = frame(w, h, [](int x, int y) { return staircase(x, y, 255); });
  Image plain, filtered;
  convertFrame(rgba.data(), w, h, false, plain);
  convertFrame(rgba.data(), w, h, true, filtered);
  int softened = 0;
  for (int y = 1; y + 1 < h; ++y) {
    for (int x = 1; x + 1 < w; ++x) {
      const int before = plain.pixel(x, y)[0], after = filtered.pixel(x, y)[0];
      const bool nearEdge = std::abs(x - (y / 2 + 4)) <= 2;
      if (!nearEdge) {
        EXPECT_EQ(after, before) << x << "," << y;  // flat areas untouched
      }
      if (after != 0 && after != 255) ++softened;
    }
  }
  EXPECT_GT(softened, h / 2);  // intermediate shades along the staircase
}

TEST(FrameFilter, LeavesSelfAntiAliasedPixelsAlone) {
  // Alpha 0 marks sky and ground, which anti-alias themselves: the same staircase is kept as is.
  const int w = 24, h = 24;
  const auto rgba = frame(w, h, [](int x, int y) { return staircase(x, y, 0); });
  Image plain, filtered;
  convertFrame(rgba.data(), w, h, false, plain);
  convertFrame(rgba.data(), w, h, true, filtered);
  EXPECT_EQ(plain.pixels, filtered.pixels);
}

TEST(FrameFilter, LargeFramesSplitBetweenThreadsGiveTheSameRows) {
  // A pattern repeating every 16 rows over a frame big enough for the two-thread path: rows one
  // period apart, on either side of the split, must come out identical.
  const int w = 640, h = 480;
  const auto rgba = frame(w, h, [](int x, int y) { return staircase(x % 40, y % 16, 255); });
  Image out;
  convertFrame(rgba.data(), w, h, true, out);
  for (int y = 16; y < h - 16; ++y) {
    const int twin = y < h / 2 ? y + 16 * 10 : y - 16 * 10;
    if (twin <= 0 || twin >= h - 1) continue;
    ASSERT_EQ(0, std::memcmp(out.pixel(0, y), out.pixel(0, twin), static_cast<std::size_t>(w) * 3)) << y;
  }
}

TEST(FrameFilter, RejectsBadInput) {
  Image out;
  EXPECT_THROW(convertFrame(nullptr, 4, 4, true, out), InvalidArgument);
  std::vector<std::uint8_t> rgba(16, 0);
  EXPECT_THROW(convertFrame(rgba.data(), 0, 4, true, out), InvalidArgument);
}

}  // namespace
}  // namespace rope::render
