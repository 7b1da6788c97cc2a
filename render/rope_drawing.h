// SPDX-License-Identifier: MIT
#pragma once
// Adds a rope, given as plain spline data, to a scene: the swept tube and optionally its control
// polygon as an overlay (so the knot vector's adaptivity is visible, with alternating span colours).

#include "render/polyline_mesh.h"
#include "render/scene.h"
#include "render/tube_mesh.h"

namespace rope::render {

struct RopeStyle {
  TubeOptions tube;
  bool showControlPolygon = false;
  PolylineOptions controlPolygon;
};

// Throws like buildTubeMesh / buildPolylineMesh; scene is unchanged on error.
void addRope(Scene& scene, const KnotVector& knots, const PointList& points, const RopeStyle& style = {});

}  // namespace rope::render
