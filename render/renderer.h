// SPDX-License-Identifier: MIT
#pragma once
// Offscreen renderer for an extracted Scene: soft key light with a shadow map, hemisphere ambient,
// a ground grid, sky gradient with distance haze, and multisample anti-aliasing, read back into an
// RGB image. Runs on OSMesa/llvmpipe; GL types stay out of this header.
//
// Threading: a Renderer owns its GL context and must be used from one thread at a time; each call
// makes the context current on the calling thread. Floating-point exception traps set by the
// caller are masked during GL work and restored afterwards (see fp_environment.h).

#include <memory>
#include <string>

#include "render/camera.h"
#include "render/image.h"
#include "render/scene.h"

namespace rope::render {

struct RenderSettings {
  int width = 1280;             // pixels, 1..8192
  int height = 720;             // pixels, 1..8192
  // Anti-aliasing. The post filter (edge-directed blending, FXAA-like, see frame_filter.h) is
  // cheap; MSAA gives cleaner edges but roughly doubles the frame time on llvmpipe. They combine.
  bool postAntiAliasing = true;
  int samples = 1;              // MSAA samples per pixel: 1 (off), 2, 4 or 8
  bool shadows = true;
  // Texels per side, 256..8192. The light frustum is fitted to the scene each frame, so 1024 gives
  // crisp shadows for scenes a few metres across; 2048 cost 4-12 ms more per 1280x720 frame in our
  // llvmpipe measurements on two cores.
  int shadowMapSize = 1024;
  // Direction the light travels (from the light towards the scene); any non-zero length.
  Vec3 lightDirection{1.0, -1.2, -0.55};
  // A grid-covered ground is drawn at y = min(0, lowest point of the scene) when the scene has no
  // Material::Ground item of its own (Y is up, as in Bullet's defaults).
  bool autoGround = true;
  double gridSpacing = 0.25;    // metres between minor grid lines (every 5th is a major line), > 0
  Rgb horizonColour{0.86f, 0.89f, 0.93f};  // sky at the horizon and distance haze (sRGB)
  Rgb zenithColour{0.52f, 0.66f, 0.86f};   // sky at the top of the image (sRGB)

  // Throws InvalidArgument naming the field ("settings.width", ...).
  void validate() const;
};

class Renderer {
 public:
  // Creates the GL context and GPU resources. Throws InvalidArgument for bad settings and
  // std::runtime_error if OSMesa cannot provide an OpenGL 3.3 core context.
  explicit Renderer(const RenderSettings& settings = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Draws scene from camera and reads the frame back into out (resized to the settings' size,
  // rows top to bottom). Throws InvalidArgument for a bad camera or a mesh whose indices are not
  // triangles of its own vertices ("mesh.indices[i]"); std::runtime_error on a GL error.
  void render(const Scene& scene, const Camera& camera, Image& out);
  Image render(const Scene& scene, const Camera& camera);
  // The same with the camera from frameScene().
  Image render(const Scene& scene);

  // A camera framing the scene's bounds (ground excluded) at this renderer's aspect ratio; a
  // default camera for an empty scene.
  Camera frameScene(const Scene& scene) const;

  const RenderSettings& settings() const;
  // GL_VERSION / GL_RENDERER of the context.
  std::string glVersion() const;
  std::string glRenderer() const;
  // Meshes currently held on the GPU: a mesh is uploaded the first time it is drawn and released at
  // the end of the first frame after which nothing (no Scene, no cache) holds it any more.
  std::size_t gpuMeshCount() const;
  // Meshes uploaded since construction (the per-frame cost of moving ropes shows here).
  std::size_t uploadCount() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rope::render
