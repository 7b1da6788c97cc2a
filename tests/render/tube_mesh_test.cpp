// SPDX-License-Identifier: MIT
#include "render/tube_mesh.h"

#include <gtest/gtest.h>

#include <cmath>

#include "mesh_checks.h"
#include "rope/common/error.h"
#include "rope/spline/bspline_curve.h"

namespace rope::render {
namespace {

using test::normal;
using test::position;
constexpr double kPi = 3.14159265358979323846;

// A planar arc-like S curve in the x-y plane.
PointList planarPoints() {
  return {Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(2, 0, 0), Vec3(3, -1, 0), Vec3(4, 0, 0), Vec3(5, 1, 0)};
}

TEST(TubeMesh, VertexAndTriangleCountsFollowTheDocumentedLayout) {
  const KnotVector knots = KnotVector::clampedUniform(3, 6);  // 3 non-empty spans
  ASSERT_EQ(nonEmptySpanCount(knots), 3);
  TubeOptions options;
  options.sides = 12;
  options.samplesPerSpan = 5;
  const Mesh capped = buildTubeMesh(knots, planarPoints(), options);
  EXPECT_EQ(capped.vertices.size(), 3u * 6u * 12u + 2u * 13u);
  EXPECT_EQ(capped.triangleCount(), 3u * 5u * 12u * 2u + 2u * 12u);
  test::expectWellFormed(capped);
  test::expectClosed(capped, 1e-4);

  options.capEnds = false;
  const Mesh open = buildTubeMesh(knots, planarPoints(), options);
  EXPECT_EQ(open.vertices.size(), 3u * 6u * 12u);
  EXPECT_EQ(open.triangleCount(), 3u * 5u * 12u * 2u);
}

TEST(TubeMesh, EmptySpansFromRepeatedKnotsAreSkipped) {
  // Interior knot 0.5 doubled: spans [0, .5), [.5, .5) (empty), [.5, 1).
  const KnotVector knots(3, {0, 0, 0, 0, 0.5, 0.5, 1, 1, 1, 1});
  ASSERT_EQ(knots.controlPointCount(), 6);
  EXPECT_EQ(nonEmptySpanCount(knots), 2);
  TubeOptions options;
  options.capEnds = false;
  const Mesh mesh = buildTubeMesh(knots, planarPoints(), options);
  EXPECT_EQ(mesh.vertices.size(), static_cast<std::size_t>(2 * (options.samplesPerSpan + 1) * options.sides));
}

TEST(TubeMesh, RingsSitOnTheCurveAtTheRadiusWithRadialNormals) {
  const KnotVector knots = KnotVector::clampedUniform(3, 6);
  const PointList points = planarPoints();
  TubeOptions options;
  options.radius = 0.1;
  options.sides = 16;
  options.samplesPerSpan = 4;
  options.capEnds = false;
  const Mesh mesh = buildTubeMesh(knots, points, options);
  const int ringSize = options.sides;
  int ring = 0;
  for (int span = 0; span < 3; ++span) {
    const double s0 = knots[3 + span], s1 = knots[4 + span];
    for (int j = 0; j <= options.samplesPerSpan; ++j, ++ring) {
      const double s = s0 + (s1 - s0) * j / options.samplesPerSpan;
      const CurvePoint c = evaluateCurve(knots, points, s);
      const Vec3 tangent = c.firstDerivative.normalized();
      for (int q = 0; q < ringSize; ++q) {
        const Vertex& v = mesh.vertices[static_cast<std::size_t>(ring * ringSize + q)];
        const Vec3 offset = position(v) - c.position;
        EXPECT_NEAR(offset.norm(), 0.1, 1e-6);
        EXPECT_NEAR(offset.dot(tangent), 0.0, 1e-6);  // ring plane normal to the tangent
        EXPECT_NEAR(normal(v).dot(offset.normalized()), 1.0, 1e-5);  // outward radial normal
      }
    }
  }
}

TEST(TubeMesh, ParallelTransportDoesNotTwistAPlanarCurve) {
  // For a planar curve the rotation-minimising frame keeps the binormal constant: the first ring
  // vertex (angle 0, the transported normal) stays in one plane, either in the curve's plane or
  // perpendicular to it, for every ring.
  const KnotVector knots = KnotVector::clampedUniform(3, 6);
  TubeOptions options;
  options.capEnds = false;
  const Mesh mesh = buildTubeMesh(knots, planarPoints(), options);
  const int rings = 3 * (options.samplesPerSpan + 1);
  const Vec3 first = normal(mesh.vertices[0]);
  const double firstZ = first.z();
  for (int ring = 0; ring < rings; ++ring) {
    const Vec3 n = normal(mesh.vertices[static_cast<std::size_t>(ring * options.sides)]);
    EXPECT_NEAR(n.z(), firstZ, 1e-4) << "ring " << ring;
  }
}

TEST(TubeMesh, TwistAlongAHelixMatchesTheRotationMinimisingFrame) {
  // Frames must change continuously: neighbouring rings' first vertices rotate by a small angle.
  PointList helix;
  for (int i = 0; i < 12; ++i) helix.push_back(Vec3(std::cos(0.6 * i), std::sin(0.6 * i), 0.2 * i));
  const KnotVector knots = KnotVector::clampedUniform(3, 12);
  TubeOptions options;
  options.capEnds = false;
  options.samplesPerSpan = 6;
  const Mesh mesh = buildTubeMesh(knots, helix, options);
  const int rings = nonEmptySpanCount(knots) * (options.samplesPerSpan + 1);
  for (int ring = 1; ring < rings; ++ring) {
    const Vec3 a = normal(mesh.vertices[static_cast<std::size_t>((ring - 1) * options.sides)]);
    const Vec3 b = normal(mesh.vertices[static_cast<std::size_t>(ring * options.sides)]);
    EXPECT_GT(a.dot(b), std::cos(kPi / 8)) << "frame jumps at ring " << ring;
  }
}

TEST(TubeMesh, AlternatingSpanColours) {
  const KnotVector knots = KnotVector::clampedUniform(3, 6);
  TubeOptions options;
  options.alternateSpanColours = true;
  options.capEnds = false;
  options.colour = Rgb(1.0f, 0.0f, 0.0f);
  options.alternateColour = Rgb(0.0f, 0.0f, 1.0f);
  const Mesh mesh = buildTubeMesh(knots, planarPoints(), options);
  const std::size_t perSpan = static_cast<std::size_t>((options.samplesPerSpan + 1) * options.sides);
  for (std::size_t span = 0; span < 3; ++span) {
    for (std::size_t i = span * perSpan; i < (span + 1) * perSpan; ++i) {
      const auto& c = mesh.vertices[i].colour;
      if (span % 2 == 0) {
        EXPECT_EQ(c[0], 1.0f);
        EXPECT_EQ(c[2], 0.0f);
      } else {
        EXPECT_EQ(c[0], 0.0f);
        EXPECT_EQ(c[2], 1.0f);
      }
    }
  }
  options.alternateSpanColours = false;
  for (const Vertex& v : buildTubeMesh(knots, planarPoints(), options).vertices) EXPECT_EQ(v.colour[0], 1.0f);
}

TEST(TubeMesh, CapsCloseTheEndsFacingAlongTheTangent) {
  const KnotVector knots = KnotVector::clampedUniform(3, 6);
  const PointList points = planarPoints();
  TubeOptions options;
  const Mesh mesh = buildTubeMesh(knots, points, options);
  const std::size_t startCap = static_cast<std::size_t>(3 * (options.samplesPerSpan + 1) * options.sides);
  const Vec3 startTangent = evaluateCurve(knots, points, 0.0).firstDerivative.normalized();
  const Vec3 endTangent = evaluateCurve(knots, points, 1.0).firstDerivative.normalized();
  EXPECT_NEAR((position(mesh.vertices[startCap]) - points.front()).norm(), 0.0, 1e-6);
  EXPECT_NEAR(normal(mesh.vertices[startCap]).dot(-startTangent), 1.0, 1e-6);
  const std::size_t endCap = startCap + static_cast<std::size_t>(options.sides + 1);
  EXPECT_NEAR((position(mesh.vertices[endCap]) - points.back()).norm(), 0.0, 1e-6);
  EXPECT_NEAR(normal(mesh.vertices[endCap]).dot(endTangent), 1.0, 1e-6);
}

TEST(TubeMesh, CurveWithAStationaryStartStillGetsATube) {
  // Coincident first control points: C'(s0) = 0, the tangent is borrowed from further along.
  const PointList points{Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 1, 0)};
  const Mesh mesh = buildTubeMesh(KnotVector::clampedUniform(3, 5), points, TubeOptions{});
  test::expectWellFormed(mesh);
  for (const Vertex& v : mesh.vertices) {
    for (float x : v.position) EXPECT_TRUE(std::isfinite(x));
  }
}

TEST(TubeMesh, RejectsBadInputNamingTheParameter) {
  const KnotVector knots = KnotVector::clampedUniform(3, 6);
  auto expectParameter = [&](const PointList& points, const TubeOptions& options, const std::string& parameter) {
    try {
      buildTubeMesh(knots, points, options);
      ADD_FAILURE() << "no exception for " << parameter;
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.parameter(), parameter) << e.what();
    }
  };
  TubeOptions options;
  PointList points = planarPoints();
  PointList nonFinite = points;
  nonFinite[2].y() = std::nan("");
  expectParameter(nonFinite, options, "points[2]");
  nonFinite[2].y() = INFINITY;
  expectParameter(nonFinite, options, "points[2]");
  expectParameter(PointList(points.begin(), points.end() - 1), options, "points.size()");
  TubeOptions bad = options;
  bad.radius = 0.0;
  expectParameter(points, bad, "options.radius");
  bad.radius = -0.1;
  expectParameter(points, bad, "options.radius");
  bad.radius = std::nan("");
  expectParameter(points, bad, "options.radius");
  bad = options;
  bad.sides = 2;
  expectParameter(points, bad, "options.sides");
  bad = options;
  bad.samplesPerSpan = 0;
  expectParameter(points, bad, "options.samplesPerSpan");
  bad = options;
  bad.colour = Rgb(1.5f, 0.0f, 0.0f);
  expectParameter(points, bad, "options.colour[0]");
}

}  // namespace
}  // namespace rope::render
