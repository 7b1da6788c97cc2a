// SPDX-License-Identifier: MIT
#pragma once
// Pinhole camera: look-at placement and a perspective projection (OpenGL clip conventions, right
// handed, looking down -Z in view space). Lengths in metres, angles in degrees.

#include <Eigen/Core>

#include "render/bounding_box.h"

namespace rope::render {

struct Camera {
  Vec3 eye{3.0, 2.0, 4.0};
  Vec3 target{0.0, 0.0, 0.0};
  Vec3 up{0.0, 1.0, 0.0};            // need not be unit; must not be parallel to eye - target
  double verticalFovDegrees = 40.0;  // (0, 170]
  double nearPlane = 0.05;           // metres, > 0
  double farPlane = 200.0;           // metres, > nearPlane

  // Throws InvalidArgument naming the field ("camera.eye", "camera.up", ...).
  void validate() const;
  Eigen::Matrix4d viewMatrix() const;
  // aspect = width / height, > 0.
  Eigen::Matrix4d projectionMatrix(double aspect) const;
};

// Default viewing direction for framing: from the target towards the eye, a three-quarter view
// from slightly above (Y up).
inline Vec3 defaultViewDirection() { return Vec3(0.55, 0.45, 1.0); }

// A camera looking along -viewDirection at the centre of box, far enough away that the box's
// bounding sphere fits the view at the given aspect (width / height), with a small margin.
// Throws InvalidArgument for an empty "box", a zero or non-finite "viewDirection", or a bad "aspect".
Camera frameBoundingBox(const BoundingBox& box, double aspect, const Vec3& viewDirection = defaultViewDirection(),
                        double verticalFovDegrees = 40.0);

}  // namespace rope::render
