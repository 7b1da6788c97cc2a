// SPDX-License-Identifier: MIT
#pragma once
// A rope drawn as a smooth tube swept along its B-spline: rings of vertices sampled per knot span,
// oriented by parallel-transport frames (rotation-minimising, so the tube does not twist where the
// curve bends) with per-vertex normals. Knot spans can be coloured alternately so the adaptivity of
// the knot vector is visible (as in the paper's knot-tying figure).

#include "render/mesh.h"
#include "rope/common/types.h"
#include "rope/spline/knot_vector.h"

namespace rope::render {

struct TubeOptions {
  double radius = 0.02;        // metres, > 0
  int sides = 16;              // vertices around each ring, 3..256
  int samplesPerSpan = 8;      // ring intervals per non-empty knot span, 1..1024
  bool capEnds = true;         // flat discs closing both ends
  Rgb colour{0.89f, 0.56f, 0.22f};           // sRGB, every channel in [0, 1]
  bool alternateSpanColours = false;          // odd spans (in order along the curve) use...
  Rgb alternateColour{0.95f, 0.93f, 0.87f};  // ...this colour (off-white: a striped rope)
};

// Vertex layout (the tests rely on it): for each non-empty knot span in order, samplesPerSpan + 1
// rings of `sides` vertices (rings at span boundaries are duplicated so that each span can carry its
// own colour), then, if capEnds, the start cap (centre, then `sides` rim vertices) and the end cap.
// Vertex count: spans * (samplesPerSpan + 1) * sides + (capEnds ? 2 * (sides + 1) : 0).
//
// Throws InvalidArgument naming the parameter: "points.size()" not equal to
// knots.controlPointCount(), "points[i]" with a non-finite coordinate, or a bad option
// ("options.radius", "options.sides", "options.samplesPerSpan", "options.colour[c]", ...).
Mesh buildTubeMesh(const KnotVector& knots, const PointList& points, const TubeOptions& options = {});

// Number of knot spans [s_k, s_k+1) of positive length within the valid range.
int nonEmptySpanCount(const KnotVector& knots);

}  // namespace rope::render
