// SPDX-License-Identifier: MIT
#include "render/rope_drawing.h"
#include "render/primitive_mesh.h"

#include <gtest/gtest.h>

#include <cmath>

#include "mesh_checks.h"
#include "rope/common/error.h"
#include "test_scene.h"

namespace rope::render {
namespace {

TEST(RopeDrawing, TubeAloneOrWithItsControlPolygonOverlay) {
  Scene scene;
  RopeStyle style;
  addRope(scene, test::ropeKnots(), test::ropePoints(), style);
  ASSERT_EQ(scene.items.size(), 1u);
  EXPECT_EQ(scene.items[0].material, Material::Surface);

  style.showControlPolygon = true;
  addRope(scene, test::ropeKnots(), test::ropePoints(), style);
  ASSERT_EQ(scene.items.size(), 3u);
  EXPECT_EQ(scene.items[2].material, Material::Overlay);
  // The overlay reaches every control point.
  const BoundingBox polygon = meshBounds(*scene.items[2].mesh);
  for (const Vec3& p : test::ropePoints()) {
    EXPECT_TRUE((p.array() >= polygon.min.array() - 1e-6).all() && (p.array() <= polygon.max.array() + 1e-6).all());
  }
}

TEST(RopeDrawing, PolylineMeshHasABallPerPointAndATubePerSegment) {
  PolylineOptions options;
  options.sides = 6;
  const PointList points{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0)};  // one zero-length segment
  const Mesh mesh = buildPolylineMesh(points, options);
  test::expectWellFormed(mesh);
  const std::size_t ballVertices = makeSphere(1.0, options.sides).vertices.size();
  const std::size_t segmentVertices = 2u * 6u;
  EXPECT_EQ(mesh.vertices.size(), 4u * ballVertices + 2u * segmentVertices);
  for (const Vertex& v : mesh.vertices) EXPECT_FLOAT_EQ(v.colour[0], options.colour.x());
}

TEST(RopeDrawing, BadInputLeavesTheSceneUnchanged) {
  Scene scene;
  PointList points = test::ropePoints();
  points[1].x() = std::nan("");
  try {
    addRope(scene, test::ropeKnots(), points);
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.parameter(), "points[1]");
  }
  RopeStyle style;
  style.showControlPolygon = true;
  style.controlPolygon.lineRadius = 0.0;
  EXPECT_THROW(addRope(scene, test::ropeKnots(), test::ropePoints(), style), InvalidArgument);
  EXPECT_TRUE(scene.items.empty());
}

}  // namespace
}  // namespace rope::render
