// SPDX-License-Identifier: MIT
#include "rope/spline/control_polygon.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "rope/common/error.h"
#include "rope/spline/point_validation.h"

namespace rope {
namespace {

// Sides a = q_i - q_{i-1} and b = q_{i+1} - q_i of the polygon points[0 .. count-1], validated.
void sides(const Vec3* points, std::size_t count, int i, Vec3& a, Vec3& b) {
  const int n = static_cast<int>(count);
  if (i < 1 || i > n - 2) {
    throw InvalidArgument("i", std::to_string(i),
                          "must be an interior vertex in 1..points.size()-2 = " + std::to_string(n - 2));
  }
  requireFinitePoints("points", points, count, static_cast<std::size_t>(i - 1), static_cast<std::size_t>(i + 1));
  a = points[i] - points[i - 1];
  b = points[i + 1] - points[i];
}

void sides(const PointList& points, int i, Vec3& a, Vec3& b) { sides(points.data(), points.size(), i, a, b); }

}  // namespace

double bendMeasure(const PointList& points, int i) { return bendMeasure(points.data(), points.size(), i); }

double bendMeasure(const Vec3* points, std::size_t count, int i) {
  Vec3 a;
  Vec3 b;
  sides(points, count, i, a, b);
  const double lengths = a.norm() * b.norm();
  if (!(lengths > 0.0)) return 0.0;  // a zero-length side has no direction to bend
  // [A] eq. 13 with the corrected sign (docs/method.md eq. 27); the clamp absorbs rounding of |cos| past 1.
  const double cosine = std::clamp(a.dot(b) / lengths, -1.0, 1.0);
  return 0.5 * (1.0 - cosine);
}

double includedAngle(const PointList& points, int i) {
  Vec3 a;
  Vec3 b;
  sides(points, i, a, b);
  const double pi = std::acos(-1.0);
  if (!(a.norm() > 0.0 && b.norm() > 0.0)) return pi;
  // atan2 keeps full accuracy near straight and near folded, where acos of the cosine does not.
  const double turn = std::atan2(a.cross(b).norm(), a.dot(b));
  return pi - turn;
}

double bendMeasureFromAngle(double includedAngleRadians) {
  requireFinite("includedAngleRadians", includedAngleRadians);
  const double pi = std::acos(-1.0);
  if (includedAngleRadians < 0.0 || includedAngleRadians > pi) {
    throw InvalidArgument("includedAngleRadians", formatValue(includedAngleRadians), "must be in [0, pi]");
  }
  return 0.5 * (1.0 + std::cos(includedAngleRadians));  // [B]; docs/method.md eq. 28
}

double angleFromBendMeasure(double bendMeasure) {
  requireFinite("bendMeasure", bendMeasure);
  if (bendMeasure < 0.0 || bendMeasure > 1.0) {
    throw InvalidArgument("bendMeasure", formatValue(bendMeasure), "must be in [0, 1]");
  }
  return std::acos(2.0 * bendMeasure - 1.0);
}

double polygonLength(const PointList& points) {
  requireFinitePoints("points", points);
  double length = 0.0;
  for (size_t i = 1; i < points.size(); ++i) {
    length += (points[i] - points[i - 1]).norm();
  }
  return length;
}

}  // namespace rope
