// SPDX-License-Identifier: MIT
#include "render/renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfenv>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <vector>

#include "render/png_writer.h"
#include "render/rope_drawing.h"
#include "rope/common/error.h"
#include "rope/spline/bspline_curve.h"
#include "test_scene.h"

namespace rope::render {
namespace {

constexpr int kWidth = 640;
constexpr int kHeight = 360;

struct Pixel {
  int x, y;
  bool inside;
};

Pixel toPixel(const Camera& camera, const Vec3& p) {
  const Eigen::Vector4d clip =
      camera.projectionMatrix(static_cast<double>(kWidth) / kHeight) * camera.viewMatrix() * p.homogeneous();
  const double x = (clip.x() / clip.w() + 1.0) * 0.5 * kWidth;
  const double y = (1.0 - clip.y() / clip.w()) * 0.5 * kHeight;
  return Pixel{static_cast<int>(x), static_cast<int>(y), clip.w() > 0 && x >= 0 && x < kWidth && y >= 0 && y < kHeight};
}

double luminance(const std::uint8_t* p) { return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2]; }

// The rope's orange (0.89, 0.56, 0.22) stays red > green > blue under any light.
bool isRopeColoured(const std::uint8_t* p) { return p[0] > p[1] + 25 && p[1] > p[2] + 25; }

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

class RendererTest : public ::testing::Test {
 protected:
  static RenderSettings smallSettings() {
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    return settings;
  }
  test::TestWorld world;
  ShapeMeshCache cache;
};

TEST_F(RendererTest, ReferenceScenePixelStatistics) {
  Renderer renderer(smallSettings());
  const Scene scene = test::buildScene(world, cache);
  const Camera camera = renderer.frameScene(scene);
  const Image image = renderer.render(scene, camera);
  ASSERT_EQ(image.width, kWidth);
  ASSERT_EQ(image.height, kHeight);
  const std::string path = ::testing::TempDir() + "splinerope_render_reference.png";
  writePng(path, image);
  std::printf("reference image: %s (%s)\n", path.c_str(), renderer.glRenderer().c_str());

  // Rope pixels where the rope is: project points along the centre line.
  const KnotVector knots = test::ropeKnots();
  const PointList points = test::ropePoints();
  int onRope = 0, samples = 0;
  for (int i = 0; i <= 100; ++i) {
    const Pixel pixel = toPixel(camera, curvePosition(knots, points, i / 100.0));
    ASSERT_TRUE(pixel.inside);
    ++samples;
    if (isRopeColoured(image.pixel(pixel.x, pixel.y))) ++onRope;
  }
  EXPECT_GE(onRope, samples * 9 / 10) << onRope << " of " << samples;

  // Background elsewhere: the top rows are sky (bluish, no rope or object colours, smooth).
  int ropeColouredElsewhere = 0;
  for (int x = 0; x < kWidth; ++x) {
    for (int y = 0; y < 8; ++y) {
      const std::uint8_t* p = image.pixel(x, y);
      EXPECT_GT(p[2], p[0]) << "sky at " << x << "," << y;
      EXPECT_NEAR(p[2], image.pixel(kWidth / 2, y)[2], 3);
    }
  }
  // Rope colour appears only near the rope: count it in the image corners.
  for (int y = kHeight - 30; y < kHeight; ++y) {
    for (int x = 0; x < 30; ++x) ropeColouredElsewhere += isRopeColoured(image.pixel(x, y));
  }
  EXPECT_EQ(ropeColouredElsewhere, 0);

  // Shadow darker than lit ground: ground points near the objects, classified by ray casts
  // towards the light (shadowed or lit) and from the camera (visible), compared by median luma.
  const Vec3 towardsLight = -renderer.settings().lightDirection.normalized();
  auto blocked = [&](const Vec3& from, const Vec3& to) {
    btCollisionWorld::ClosestRayResultCallback ray(btVector3(from.x(), from.y(), from.z()),
                                                   btVector3(to.x(), to.y(), to.z()));
    world.world.rayTest(ray.m_rayFromWorld, ray.m_rayToWorld, ray);
    return ray.hasHit();
  };
  std::vector<double> shadowed, lit;
  for (double x = -2.5; x <= 2.5; x += 0.05) {
    for (double z = -2.0; z <= 2.0; z += 0.05) {
      const Vec3 ground(x, 0.0, z);
      const Vec3 lifted = ground + Vec3(0, 1e-3, 0);
      const Pixel pixel = toPixel(camera, ground);
      if (!pixel.inside) continue;
      const Vec3 toEye = camera.eye - lifted;
      if (blocked(lifted + 1e-3 * toEye.normalized(), camera.eye)) continue;  // hidden by an object
      const std::uint8_t* p = image.pixel(pixel.x, pixel.y);
      if (isRopeColoured(p)) continue;
      (blocked(lifted + 1e-3 * towardsLight, lifted + 5.0 * towardsLight) ? shadowed : lit).push_back(luminance(p));
    }
  }
  ASSERT_GT(shadowed.size(), 50u);
  ASSERT_GT(lit.size(), 500u);
  std::printf("ground luma: shadowed median %.1f (%zu points), lit median %.1f (%zu points)\n", median(shadowed),
              shadowed.size(), median(lit), lit.size());
  EXPECT_LT(median(shadowed), 0.8 * median(lit));
}

TEST_F(RendererTest, AnnotatedRopeShowsBothSpanColoursAndThePolygon) {
  Renderer renderer(smallSettings());
  const Scene scene = test::buildScene(world, cache, true);
  const Camera camera = renderer.frameScene(scene);
  const Image image = renderer.render(scene, camera);
  writePng(::testing::TempDir() + "splinerope_render_annotated.png", image);
  const KnotVector knots = test::ropeKnots();
  const PointList points = test::ropePoints();
  int orange = 0, light = 0;
  for (int i = 0; i <= 100; ++i) {
    const Pixel pixel = toPixel(camera, curvePosition(knots, points, i / 100.0));
    const std::uint8_t* p = image.pixel(pixel.x, pixel.y);
    if (isRopeColoured(p)) ++orange;
    // The alternate colour is off-white: bright and unsaturated.
    if (std::min({p[0], p[1], p[2]}) > 150 && std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}) < 50) {
      ++light;
    }
  }
  EXPECT_GT(orange, 20);
  EXPECT_GT(light, 20);
}

TEST_F(RendererTest, MultisamplingGivesTheSamePicture) {
  RenderSettings settings = smallSettings();
  settings.samples = 4;
  settings.postAntiAliasing = false;
  Renderer msaa(settings);
  Renderer plain(smallSettings());
  const Scene scene = test::buildScene(world, cache);
  const Camera camera = plain.frameScene(scene);
  const Image a = msaa.render(scene, camera), b = plain.render(scene, camera);
  double difference = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) difference += std::abs(a.pixels[i] - b.pixels[i]);
  EXPECT_LT(difference / static_cast<double>(a.pixels.size()), 3.0);  // edges differ, nothing else
}

TEST_F(RendererTest, StaticMeshesUploadOnceMovingRopesAreReplaced) {
  Renderer renderer(smallSettings());
  Scene scene = test::buildScene(world, cache);
  const Camera camera = renderer.frameScene(scene);
  Image image;
  renderer.render(scene, camera, image);
  const std::size_t firstUploads = renderer.uploadCount();
  const std::size_t meshes = renderer.gpuMeshCount();
  for (int frame = 0; frame < 3; ++frame) {
    // Each frame: fresh extraction (cached shape meshes) and a rope mesh rebuilt from new points.
    scene = test::buildScene(world, cache);
    renderer.render(scene, camera, image);
  }
  EXPECT_EQ(renderer.uploadCount(), firstUploads + 3);  // only the rope each frame
  EXPECT_EQ(renderer.gpuMeshCount(), meshes);           // the old rope meshes were released
}

TEST_F(RendererTest, EmptySceneAndDefaultCamera) {
  Renderer renderer(smallSettings());
  const Image image = renderer.render(Scene{});
  EXPECT_EQ(image.width, kWidth);
  // Sky on top, ground grid below.
  EXPECT_GT(image.pixel(kWidth / 2, 0)[2], image.pixel(kWidth / 2, 0)[0]);
}

TEST_F(RendererTest, SkyGradientFillsTheWholeBandAboveTheHorizon) {
  Renderer renderer(smallSettings());
  Camera camera;  // level view: the horizon crosses the middle of the image
  camera.eye = Vec3(0, 1, 5);
  camera.target = Vec3(0, 1, 0);
  const Image image = renderer.render(Scene{}, camera);
  // Symmetric left to right (a half-drawn sky quad leaves one corner in the clear colour) and
  // bluer towards the top (zenith) than just above the horizon.
  for (int y = 0; y < kHeight / 2 - 10; y += 10) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(image.pixel(2, y)[k], image.pixel(kWidth - 3, y)[k], 2) << "row " << y;
  }
  auto blueness = [&](int y) { return image.pixel(kWidth / 2, y)[2] - image.pixel(kWidth / 2, y)[0]; };
  EXPECT_GT(blueness(0), blueness(kHeight / 2 - 10) + 20);
}

TEST_F(RendererTest, SceneWithoutAPlaneGetsAGroundUnderIt) {
  Renderer renderer(smallSettings());
  Scene scene;
  addRope(scene, test::ropeKnots(), test::ropePoints());
  const Image image = renderer.render(scene);
  // Bottom rows: the automatic ground (light grey, unsaturated), not sky.
  for (int x = 0; x < kWidth; x += 40) {
    const std::uint8_t* p = image.pixel(x, kHeight - 2);
    EXPECT_GT(std::min({p[0], p[1], p[2]}), 120);
    EXPECT_LT(std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}), 30);
  }
}

TEST_F(RendererTest, KeepsTheCallersFloatingPointTraps) {
  const int before = fegetexcept();
  ASSERT_NE(before & FE_INVALID, 0);
  Renderer renderer(smallSettings());
  renderer.render(test::buildScene(world, cache));
  EXPECT_EQ(fegetexcept(), before);
}

TEST_F(RendererTest, RejectsBadSettingsAndCameras) {
  auto expectParameter = [](const RenderSettings& settings, const std::string& parameter) {
    try {
      Renderer renderer(settings);
      ADD_FAILURE() << parameter;
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.parameter(), parameter) << e.what();
    }
  };
  RenderSettings settings = smallSettings();
  settings.width = 0;
  expectParameter(settings, "settings.width");
  settings = smallSettings();
  settings.samples = 3;
  expectParameter(settings, "settings.samples");
  settings = smallSettings();
  settings.shadowMapSize = 100;
  expectParameter(settings, "settings.shadowMapSize");
  settings = smallSettings();
  settings.lightDirection = Vec3::Zero();
  expectParameter(settings, "settings.lightDirection");
  settings = smallSettings();
  settings.gridSpacing = std::nan("");
  expectParameter(settings, "settings.gridSpacing");

  Renderer renderer(smallSettings());
  Camera camera;
  camera.eye = camera.target;
  Image image;
  EXPECT_THROW(renderer.render(Scene{}, camera, image), InvalidArgument);
  EXPECT_TRUE(image.empty());

  // A mesh indexing past its vertices never reaches GL.
  Mesh broken;
  broken.addVertex(Vec3::Zero(), Vec3::UnitY());
  broken.addTriangle(0, 0, 5);
  Scene scene;
  scene.add(std::make_shared<const Mesh>(broken));
  try {
    renderer.render(scene, Camera{}, image);
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.parameter(), "mesh.indices[2]");
  }
  EXPECT_NO_THROW(renderer.render(Scene{}, Camera{}, image));  // still usable
}

}  // namespace
}  // namespace rope::render
