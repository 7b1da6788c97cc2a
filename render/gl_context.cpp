// SPDX-License-Identifier: MIT
#include "render/gl_context.h"

#include <GL/osmesa.h>

#include <stdexcept>
#include <string>

#include "render/fp_environment.h"
#include "rope/common/error.h"

namespace rope::render {

namespace {
std::string glString(GLenum name) {
  const auto* text = reinterpret_cast<const char*>(glGetString(name));
  return text != nullptr ? text : "";
}
}  // namespace

GlContext::GlContext(int width, int height) {
  if (width < 1 || width > 16384) throw InvalidArgument("width", std::to_string(width), "must be within [1, 16384]");
  if (height < 1 || height > 16384) {
    throw InvalidArgument("height", std::to_string(height), "must be within [1, 16384]");
  }
  FloatingPointGuard guard;
  const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA,
                            OSMESA_DEPTH_BITS, 24,
                            OSMESA_STENCIL_BITS, 8,
                            OSMESA_ACCUM_BITS, 0,
                            OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION, 3,
                            OSMESA_CONTEXT_MINOR_VERSION, 3,
                            0};
  context_ = OSMesaCreateContextAttribs(attributes, nullptr);
  if (context_ == nullptr) {
    throw std::runtime_error(
        "GlContext: OSMesaCreateContextAttribs failed for an OpenGL 3.3 core context (is libOSMesa from Mesa "
        ">= 12 with llvmpipe installed? Debian: libosmesa6)");
  }
  width_ = width;
  height_ = height;
  buffer_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4, 0);
  try {
    makeCurrent();
  } catch (...) {
    OSMesaDestroyContext(context_);
    throw;
  }
  version_ = glString(GL_VERSION);
  renderer_ = glString(GL_RENDERER);
}

GlContext::~GlContext() {
  FloatingPointGuard guard;
  OSMesaDestroyContext(context_);
}

void GlContext::makeCurrent() {
  if (OSMesaGetCurrentContext() == context_) return;
  FloatingPointGuard guard;
  if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_)) {
    throw std::runtime_error("GlContext: OSMesaMakeCurrent failed for a " + std::to_string(width_) + "x" +
                             std::to_string(height_) + " RGBA buffer");
  }
}

}  // namespace rope::render

// OSMesa keeps the framebuffers that OSMesaMakeCurrent creates in a process-wide list (one per
// distinct size, reused) that is never freed, which LeakSanitizer reports at exit from every
// program that renders. This tells it to ignore allocations made inside libOSMesa, nothing else.
// Weak, so a program's own suppression list takes precedence; without a sanitizer it is unused.
extern "C" __attribute__((weak, used)) const char* __lsan_default_suppressions() { return "leak:libOSMesa.so\n"; }
