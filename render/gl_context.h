// SPDX-License-Identifier: MIT
#pragma once
// An offscreen OpenGL context through OSMesa (Mesa's llvmpipe, no display needed), OpenGL 3.3 core
// profile or newer. RAII: the context is destroyed with the object. GL stays out of this header.

#include <string>
#include <vector>

struct osmesa_context;

namespace rope::render {

class GlContext {
 public:
  // Creates the context and makes it current on this thread. width/height: size of the default
  // framebuffer, 1..16384 (InvalidArgument otherwise). Throws std::runtime_error naming what failed
  // (OSMesa context creation or OSMesaMakeCurrent) with the requested version.
  GlContext(int width, int height);
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Makes the context current on the calling thread (throws std::runtime_error on failure).
  void makeCurrent();
  int width() const { return width_; }
  int height() const { return height_; }
  // GL_VERSION and GL_RENDERER strings, e.g. "4.5 (Core Profile) Mesa 22.3.6" / "llvmpipe (...)".
  std::string version() const { return version_; }
  std::string rendererName() const { return renderer_; }

 private:
  osmesa_context* context_ = nullptr;
  std::vector<unsigned char> buffer_;  // the default framebuffer's RGBA storage
  int width_ = 0;
  int height_ = 0;
  std::string version_;
  std::string renderer_;
};

}  // namespace rope::render
