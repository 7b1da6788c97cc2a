// SPDX-License-Identifier: MIT
// Uses SplineRope::render: renders a frame with and without a rope tube, headless (OSMesa), and
// checks that the rope shows, then writes the frame as PNG.
#include <cstdio>
#include <cstdlib>

#include "render/png_writer.h"
#include "render/renderer.h"
#include "render/rope_drawing.h"
#include "rope/spline/curve_interpolation.h"

int main() {
  const rope::Interpolation path = rope::interpolatePolyline({{-0.5, 0.3, 0}, {0, 0.5, 0.1}, {0.5, 0.3, 0}, {0.8, 0.6, 0}});
  rope::render::RenderSettings settings;
  settings.width = 160;
  settings.height = 120;
  rope::render::Renderer renderer(settings);
  rope::render::Scene withRope, without;
  rope::render::RopeStyle style;
  style.tube.radius = 0.03;
  rope::render::addRope(withRope, path.curve.knots(), path.curve.controlPoints(), style);
  const rope::render::Camera camera = renderer.frameScene(withRope);
  const rope::render::Image a = renderer.render(withRope, camera);
  const rope::render::Image b = renderer.render(without, camera);
  int differing = 0;
  for (size_t i = 0; i < a.pixels.size(); i += 3)
    if (std::abs(a.pixels[i] - b.pixels[i]) + std::abs(a.pixels[i + 1] - b.pixels[i + 1]) +
            std::abs(a.pixels[i + 2] - b.pixels[i + 2]) > 30)
      ++differing;
  rope::render::writePng("frame.png", a);
  std::printf("%s: %d of %d pixels show the rope\n", renderer.glRenderer().c_str(), differing, 160 * 120);
  return differing > 300 ? 0 : 1;
}
