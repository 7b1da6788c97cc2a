// SPDX-License-Identifier: MIT
#include "render/png_writer.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "rope/common/error.h"

namespace rope::render {
namespace {

Image gradient(int width, int height) {
  Image image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      std::uint8_t* p = image.pixel(x, y);
      p[0] = static_cast<std::uint8_t>(x * 255 / (width - 1));
      p[1] = static_cast<std::uint8_t>(y * 255 / (height - 1));
      p[2] = static_cast<std::uint8_t>((x + y) % 256);
    }
  }
  return image;
}

TEST(Image, ConstructionAndVerticalFlip) {
  Image image = gradient(5, 4);
  EXPECT_EQ(image.pixels.size(), 5u * 4u * 3u);
  const Image original = image;
  flipVertically(image);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 5; ++x) EXPECT_EQ(image.pixel(x, y)[1], original.pixel(x, 3 - y)[1]);
  }
  flipVertically(image);
  EXPECT_EQ(image.pixels, original.pixels);
  EXPECT_THROW(Image(0, 10), InvalidArgument);
  EXPECT_THROW(Image(10, 20000), InvalidArgument);
}

TEST(PngWriter, RoundTripIsLossless) {
  const Image image = gradient(37, 21);
  const std::string path = ::testing::TempDir() + "splinerope_png_round_trip.png";
  writePng(path, image);
  std::ifstream file(path, std::ios::binary);
  char signature[8] = {};
  file.read(signature, 8);
  EXPECT_EQ(std::string(signature + 1, 3), "PNG");
  const Image back = readPng(path);
  EXPECT_EQ(back.width, 37);
  EXPECT_EQ(back.height, 21);
  EXPECT_EQ(back.pixels, image.pixels);
  std::remove(path.c_str());
}

TEST(PngWriter, ErrorsNameThePathOrTheImage) {
  try {
    writePng("/nonexistent-directory/frame.png", gradient(4, 4));
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-directory/frame.png"), std::string::npos);
  }
  EXPECT_THROW(writePng(::testing::TempDir() + "empty.png", Image{}), InvalidArgument);
  Image inconsistent = gradient(4, 4);
  inconsistent.pixels.pop_back();
  EXPECT_THROW(writePng(::testing::TempDir() + "bad.png", inconsistent), InvalidArgument);
  EXPECT_THROW(readPng("/nonexistent-directory/frame.png"), std::runtime_error);
  // Not a PNG: libpng's error comes back as an exception, not a crash.
  const std::string text = ::testing::TempDir() + "splinerope_not_a_png.png";
  std::ofstream(text) << "definitely not a png file";
  EXPECT_THROW(readPng(text), std::runtime_error);
  std::remove(text.c_str());
}

}  // namespace
}  // namespace rope::render
