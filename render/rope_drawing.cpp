// SPDX-License-Identifier: MIT
#include "render/rope_drawing.h"

namespace rope::render {

void addRope(Scene& scene, const KnotVector& knots, const PointList& points, const RopeStyle& style) {
  auto tube = std::make_shared<const Mesh>(buildTubeMesh(knots, points, style.tube));
  std::shared_ptr<const Mesh> polygon;
  if (style.showControlPolygon) polygon = std::make_shared<const Mesh>(buildPolylineMesh(points, style.controlPolygon));
  scene.add(tube);
  if (polygon) scene.add(polygon, Eigen::Isometry3d::Identity(), Rgb::Ones(), Material::Overlay);
}

}  // namespace rope::render
