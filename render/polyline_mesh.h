// SPDX-License-Identifier: MIT
#pragma once
// A polyline drawn as thin open cylinders between its points with a small ball at every point: the
// control-polygon overlay. Real geometry rather than GL lines because core-profile lines are one
// pixel wide and vanish at 720p.

#include "render/mesh.h"

namespace rope::render {

struct PolylineOptions {
  double lineRadius = 0.005;   // metres, > 0
  double pointRadius = 0.014;  // metres, >= 0 (0: no balls)
  int sides = 8;               // 3..64, also the balls' segments
  Rgb colour{0.1f, 0.1f, 0.12f};
};

// Segments of zero length are skipped. Throws InvalidArgument for a non-finite "points[i]" or a bad
// option ("options.lineRadius", ...).
Mesh buildPolylineMesh(const PointList& points, const PolylineOptions& options = {});

}  // namespace rope::render
