// SPDX-License-Identifier: MIT
#include "render/polyline_mesh.h"

#include <string>

#include "render/primitive_mesh.h"
#include "rope/common/error.h"

namespace rope::render {

Mesh buildPolylineMesh(const PointList& points, const PolylineOptions& options) {
  requirePositive("options.lineRadius", options.lineRadius);
  requireNonNegative("options.pointRadius", options.pointRadius);
  if (options.sides < 3 || options.sides > 64) {
    throw InvalidArgument("options.sides", std::to_string(options.sides), "must be within [3, 64]");
  }
  requireColour("options.colour", options.colour);
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int c = 0; c < 3; ++c) requireFinite("points[" + std::to_string(i) + "]", points[i][c]);
  }
  Mesh mesh;
  const Mesh ball = options.pointRadius > 0.0 ? makeSphere(options.pointRadius, options.sides) : Mesh{};
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!ball.empty()) mesh.append(ball, Eigen::Isometry3d(Eigen::Translation3d(points[i])));
    if (i + 1 == points.size()) break;
    const Vec3 d = points[i + 1] - points[i];
    const double length = d.norm();
    if (!(length > 1e-12)) continue;
    // The unit cylinder's +Y axis turned onto the segment.
    Eigen::Isometry3d placement = Eigen::Isometry3d::Identity();
    placement.linear() = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitY(), d / length).toRotationMatrix();
    placement.translation() = 0.5 * (points[i] + points[i + 1]);
    mesh.append(makeCylinder(options.lineRadius, 0.5 * length, options.sides, false), placement);
  }
  for (Vertex& v : mesh.vertices) v.colour = {options.colour.x(), options.colour.y(), options.colour.z()};
  return mesh;
}

}  // namespace rope::render
