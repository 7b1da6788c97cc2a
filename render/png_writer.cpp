// SPDX-License-Identifier: MIT
#include "render/png_writer.h"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "rope/common/error.h"

namespace rope::render {

namespace {

// libpng reports errors by longjmp-ing out of its own frames. The functions that call setjmp below
// hold only trivially destructible locals, so the jump skips no destructor; C++ exceptions are
// thrown only after control is back in ordinary code.
struct ErrorState {
  std::jmp_buf jump;
  char message[256];
};

void onError(png_structp png, png_const_charp message) {
  auto* state = static_cast<ErrorState*>(png_get_error_ptr(png));
  std::snprintf(state->message, sizeof state->message, "%s", message);
  std::longjmp(state->jump, 1);
}
void onWarning(png_structp, png_const_charp) {}

// Returns nullptr on success, else the libpng message (in state).
const char* writeFile(std::FILE* file, const Image& image, ErrorState& state) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, onError, onWarning);
  if (png == nullptr) return "png_create_write_struct failed";
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    return "png_create_info_struct failed";
  }
  if (setjmp(state.jump) != 0) {
    png_destroy_write_struct(&png, &info);
    return state.message;
  }
  png_init_io(png, file);
  // Fast deflate: frames may be written every step, and level 9 costs several times the time for
  // files only slightly smaller.
  png_set_compression_level(png, 3);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y) png_write_row(png, image.pixel(0, y));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return nullptr;
}

// Reads the header into width/height, then (if target is non-null) the rows. Returns nullptr on
// success, else a message.
const char* readFile(std::FILE* file, ErrorState& state, Image* target, int* width, int* height) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, onError, onWarning);
  if (png == nullptr) return "png_create_read_struct failed";
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    return "png_create_info_struct failed";
  }
  if (setjmp(state.jump) != 0) {
    png_destroy_read_struct(&png, &info, nullptr);
    return state.message;
  }
  png_init_io(png, file);
  png_read_info(png, info);
  const int colourType = png_get_color_type(png, info);
  if (png_get_bit_depth(png, info) != 8 || (colourType != PNG_COLOR_TYPE_RGB && colourType != PNG_COLOR_TYPE_RGBA)) {
    png_destroy_read_struct(&png, &info, nullptr);
    return "not an 8-bit RGB or RGBA PNG";
  }
  if (colourType == PNG_COLOR_TYPE_RGBA) png_set_strip_alpha(png);
  png_read_update_info(png, info);
  *width = static_cast<int>(png_get_image_width(png, info));
  *height = static_cast<int>(png_get_image_height(png, info));
  if (target != nullptr) {
    for (int y = 0; y < *height; ++y) png_read_row(png, target->pixel(0, y), nullptr);
    png_read_end(png, nullptr);
  }
  png_destroy_read_struct(&png, &info, nullptr);
  return nullptr;
}

}  // namespace

void writePng(const std::string& path, const Image& image) {
  if (image.width < 1 || image.height < 1 ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3) {
    throw InvalidArgument("image", std::to_string(image.width) + "x" + std::to_string(image.height),
                          "must be non-empty with width*height*3 bytes");
  }
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) throw std::runtime_error("writePng: cannot open " + path + ": " + std::strerror(errno));
  ErrorState state{};
  const char* error = writeFile(file, image, state);
  const std::string message = error != nullptr ? error : "";
  if (std::fclose(file) != 0 && message.empty()) throw std::runtime_error("writePng: error closing " + path);
  if (!message.empty()) throw std::runtime_error("writePng: " + path + ": " + message);
}

Image readPng(const std::string& path) {
  // Two passes over the header keep the row buffer (an Image, with a destructor) out of the frame
  // that setjmp returns into.
  int width = 0, height = 0;
  std::string message;
  for (int pass = 0; pass < 2 && message.empty(); ++pass) {
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (file == nullptr) throw std::runtime_error("readPng: cannot open " + path + ": " + std::strerror(errno));
    ErrorState state{};
    if (pass == 0) {
      const char* error = readFile(file, state, nullptr, &width, &height);
      if (error != nullptr) message = error;
      std::fclose(file);
      continue;
    }
    Image image(width, height);
    const char* error = readFile(file, state, &image, &width, &height);
    std::fclose(file);
    if (error == nullptr) return image;
    message = error;
  }
  throw std::runtime_error("readPng: " + path + ": " + message);
}

}  // namespace rope::render
