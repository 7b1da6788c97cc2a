// SPDX-License-Identifier: MIT
#include "render/camera.h"

#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>

#include "rope/common/error.h"
#include "support/bad_settings.h"

namespace rope::render {
namespace {

Eigen::Vector3d project(const Camera& camera, double aspect, const Vec3& p) {
  const Eigen::Vector4d clip = camera.projectionMatrix(aspect) * camera.viewMatrix() * p.homogeneous();
  return clip.head<3>() / clip.w();
}

TEST(Camera, LookAtPutsTheTargetInTheCentreAndUpIsUp) {
  Camera camera;
  camera.eye = Vec3(3, 2, 5);
  camera.target = Vec3(0.5, 0.2, -1);
  const Vec3 centre = project(camera, 16.0 / 9.0, camera.target);
  EXPECT_NEAR(centre.x(), 0.0, 1e-12);
  EXPECT_NEAR(centre.y(), 0.0, 1e-12);
  EXPECT_GT(project(camera, 16.0 / 9.0, camera.target + Vec3(0, 0.1, 0)).y(), 0.0);
  // Depth: near plane maps to -1, far plane to +1.
  Camera straight;
  straight.eye = Vec3(0, 0, 0);
  straight.target = Vec3(0, 0, -1);
  EXPECT_NEAR(project(straight, 1.0, Vec3(0, 0, -straight.nearPlane)).z(), -1.0, 1e-9);
  EXPECT_NEAR(project(straight, 1.0, Vec3(0, 0, -straight.farPlane)).z(), 1.0, 1e-9);
}

TEST(Camera, FramingKeepsEveryCornerInView) {
  BoundingBox box;
  box.extend(Vec3(-2, 0, -1));
  box.extend(Vec3(3, 1.5, 0.5));
  for (double aspect : {16.0 / 9.0, 1.0, 0.5}) {
    const Camera camera = frameBoundingBox(box, aspect);
    double largest = 0.0;
    for (int i = 0; i < 8; ++i) {
      const Vec3 corner((i & 1) ? box.max.x() : box.min.x(), (i & 2) ? box.max.y() : box.min.y(),
                        (i & 4) ? box.max.z() : box.min.z());
      const Vec3 ndc = project(camera, aspect, corner);
      EXPECT_LE(std::abs(ndc.x()), 1.0);
      EXPECT_LE(std::abs(ndc.y()), 1.0);
      EXPECT_GT(ndc.z(), -1.0);
      EXPECT_LT(ndc.z(), 1.0);
      largest = std::max({largest, std::abs(ndc.x()), std::abs(ndc.y())});
    }
    EXPECT_GT(largest, 0.85) << "the box should fill the view, aspect " << aspect;
  }
}

TEST(Camera, FramingFromStraightAbove) {
  BoundingBox box;
  box.extend(Vec3(-1, 0, -1));
  box.extend(Vec3(1, 0.2, 1));
  const Camera camera = frameBoundingBox(box, 1.0, Vec3(0, 1, 0));
  EXPECT_NO_THROW(camera.validate());
  EXPECT_GT(camera.eye.y(), 1.0);
}

TEST(Camera, ValidationNamesTheField) {
  rope::test::expectEachRejected<Camera>(
      {{"camera.target", [](Camera& c) { c.eye = c.target; }},
       {"camera.up", [](Camera& c) { c.up = c.target - c.eye; }},
       {"camera.eye", [](Camera& c) { c.eye.x() = std::nan(""); }},
       {"camera.verticalFovDegrees", [](Camera& c) { c.verticalFovDegrees = 180.0; }},
       {"camera.nearPlane", [](Camera& c) { c.nearPlane = 0.0; }},
       {"camera.farPlane", [](Camera& c) { c.farPlane = c.nearPlane; }}},
      [](const Camera& camera) { camera.validate(); });
  EXPECT_THROW(frameBoundingBox(BoundingBox{}, 1.0), InvalidArgument);
  BoundingBox box;
  box.extend(Vec3::Zero());
  EXPECT_THROW(frameBoundingBox(box, 0.0), InvalidArgument);
  EXPECT_THROW(frameBoundingBox(box, 1.0, Vec3::Zero()), InvalidArgument);
}

}  // namespace
}  // namespace rope::render
