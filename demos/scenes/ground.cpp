// SPDX-License-Identifier: MIT
#include "demos/scenes/ground.h"

#include <memory>

namespace rope::demos {

namespace {

// The renderer shades a Material::Ground item as a plane: one flat quad, normal +y.
std::shared_ptr<const render::Mesh> makeFloorQuad(double halfSize) {
  auto quad = std::make_shared<render::Mesh>();
  const Vec3 up = Vec3::UnitY();
  const auto a = quad->addVertex(Vec3(-halfSize, 0.0, -halfSize), up);
  const auto b = quad->addVertex(Vec3(-halfSize, 0.0, halfSize), up);
  const auto c = quad->addVertex(Vec3(halfSize, 0.0, halfSize), up);
  const auto d = quad->addVertex(Vec3(halfSize, 0.0, -halfSize), up);
  quad->addTriangle(a, b, c);
  quad->addTriangle(a, c, d);
  return quad;
}

}  // namespace

void addGround(render::Scene& scene, double height) {
  constexpr double kHalfSize = 40.0;  // m: reaches past the distance haze
  // One mesh shared by every frame, so the renderer uploads it once.
  static const std::shared_ptr<const render::Mesh> floor = makeFloorQuad(kHalfSize);
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.translate(Vec3(0.0, height, 0.0));
  scene.add(floor, transform, render::Rgb(0.80f, 0.80f, 0.78f), render::Material::Ground);
}

}  // namespace rope::demos
