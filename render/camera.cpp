// SPDX-License-Identifier: MIT
#include "render/camera.h"

#include <algorithm>
#include <cmath>

#include <string>

#include <Eigen/Geometry>

#include "rope/common/error.h"

namespace rope::render {

namespace {

constexpr double kPi = 3.14159265358979323846;

void requireFiniteVector(const char* parameter, const Vec3& v) {
  for (int i = 0; i < 3; ++i) requireFinite(parameter, v[i]);
}

std::string formatVector(const Vec3& v) {
  return "(" + formatValue(v.x()) + ", " + formatValue(v.y()) + ", " + formatValue(v.z()) + ")";
}

}  // namespace

void Camera::validate() const {
  requireFiniteVector("camera.eye", eye);
  requireFiniteVector("camera.target", target);
  requireFiniteVector("camera.up", up);
  const Vec3 forward = target - eye;
  if (!(forward.norm() > 1e-12)) {
    throw InvalidArgument("camera.target", formatVector(target), "must differ from camera.eye");
  }
  if (!(forward.normalized().cross(up).norm() > 1e-9 * up.norm()) || !(up.norm() > 0.0)) {
    throw InvalidArgument("camera.up", formatVector(up), "must be non-zero and not parallel to the view direction");
  }
  requirePositive("camera.verticalFovDegrees", verticalFovDegrees);
  if (verticalFovDegrees > 170.0) {
    throw InvalidArgument("camera.verticalFovDegrees", formatValue(verticalFovDegrees), "must be <= 170");
  }
  requirePositive("camera.nearPlane", nearPlane);
  requireFinite("camera.farPlane", farPlane);
  if (!(farPlane > nearPlane)) {
    throw InvalidArgument("camera.farPlane", formatValue(farPlane), "must be > camera.nearPlane");
  }
}

Eigen::Matrix4d Camera::viewMatrix() const {
  const Vec3 f = (target - eye).normalized();
  const Vec3 s = f.cross(up).normalized();
  const Vec3 u = s.cross(f);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m;
}

Eigen::Matrix4d Camera::projectionMatrix(double aspect) const {
  requirePositive("aspect", aspect);
  const double f = 1.0 / std::tan(0.5 * verticalFovDegrees * kPi / 180.0);
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m(0, 0) = f / aspect;
  m(1, 1) = f;
  m(2, 2) = (farPlane + nearPlane) / (nearPlane - farPlane);
  m(2, 3) = 2.0 * farPlane * nearPlane / (nearPlane - farPlane);
  m(3, 2) = -1.0;
  return m;
}

Camera frameBoundingBox(const BoundingBox& box, double aspect, const Vec3& viewDirection, double verticalFovDegrees) {
  if (box.empty()) throw InvalidArgument("box", "empty", "must contain at least one point");
  requireFiniteVector("box", box.min);
  requireFiniteVector("box", box.max);
  requirePositive("aspect", aspect);
  requireFiniteVector("viewDirection", viewDirection);
  if (!(viewDirection.norm() > 0.0)) throw InvalidArgument("viewDirection", formatVector(viewDirection), "must be non-zero");
  Camera camera;
  camera.verticalFovDegrees = verticalFovDegrees;
  const Vec3 back = viewDirection.normalized();  // from the target towards the eye
  const Vec3 up = back.cross(Vec3::UnitY()).norm() < 1e-6 ? Vec3::UnitZ() : Vec3::UnitY();
  const Vec3 right = up.cross(back).normalized();
  const Vec3 trueUp = back.cross(right);
  const double tanVertical = std::tan(0.5 * verticalFovDegrees * kPi / 180.0);
  const double tanHorizontal = tanVertical * aspect;
  // Each corner c (relative to the centre, in camera axes x, y and z towards the eye) is inside
  // the view when |x| <= (D - z) tan(h) and |y| <= (D - z) tan(v) for the eye distance D: take the
  // smallest D that satisfies all eight, plus a margin.
  const Vec3 center = box.center();
  double distance = 0.0;
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner((i & 1) ? box.max.x() : box.min.x(), (i & 2) ? box.max.y() : box.min.y(),
                      (i & 4) ? box.max.z() : box.min.z());
    const Vec3 c = corner - center;
    const double z = c.dot(back);
    distance = std::max(distance, z + std::abs(c.dot(right)) / tanHorizontal);
    distance = std::max(distance, z + std::abs(c.dot(trueUp)) / tanVertical);
  }
  distance = std::max(1.08 * distance, 1e-2);
  camera.target = center;
  camera.eye = center + distance * back;
  camera.up = up;
  const double radius = box.radius();
  camera.nearPlane = std::max(1e-3, 0.5 * (distance - radius) > 0.0 ? 0.5 * (distance - radius) : 0.01 * distance);
  camera.farPlane = std::max(200.0, 50.0 * (distance + radius));
  camera.validate();
  return camera;
}

}  // namespace rope::render
