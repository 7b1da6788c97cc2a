// SPDX-License-Identifier: MIT
#pragma once
// "rest": straight ropes lying at rest on a flat static surface, the commonest contact there is:
// a btStaticPlaneShape, a btBoxShape or a btBvhTriangleMeshShape (a flat grid of 10 cm squares, each
// cut into two triangles, so a rope lies across triangle edges and diagonals). Each rope (default
// RodSettings and BulletRopeSettings: 5 mm radius, 1 m, 16 initial control points) lies along x with
// its centre line one radius plus `gap` above the surface; the ropes are side by side along z,
// `spacing` apart. Nothing happens but gravity and contact, so a good contact model keeps each rope
// straight, still and coarse: no knot insertion and no more control points than it started with.
// Also the SplineRope side of the benchmark of ropes resting on a box (tests/bench).

#include <memory>
#include <vector>

#include "bullet_bridge/rope_object.h"
#include "demos/scenes/world_scene.h"

namespace rope::demos {

struct RestingRopeSceneSettings {
  enum class Surface { kPlane, kBox, kTriangleMesh };
  Surface surface = Surface::kBox;
  int ropeCount = 1;              // >= 1
  double ropeLength = 1.0;        // m, > 0
  double spacing = 0.05;          // m, > 2 rope radii: distance between neighbouring ropes
  double gap = 0.0;               // m, >= 0: initial gap between each rope and the surface
  double timeStep = 1.0 / 240.0;  // s, > 0
  RodSettings rod;                // defaults (restLength is set to ropeLength)
  bullet::BulletRopeSettings bridge;  // defaults
};

class RestingRopeScene : public WorldScene {
 public:
  // Throws InvalidArgument naming the field for bad settings.
  explicit RestingRopeScene(const RestingRopeSceneSettings& settings);
  ~RestingRopeScene() override;

  // Sums over the ropes (controlPoints too); maxima of strain and penetration.
  StepMeasurements step() override;
  StepMeasurements measure() const override;
  void draw(render::Scene& scene) const override;
  std::optional<render::Camera> camera() const override;

  int ropeCount() const { return static_cast<int>(ropes_.size()); }
  const bullet::RopeObject& rope(int i) const { return *ropes_.at(static_cast<std::size_t>(i)); }
  // Largest control point count over the ropes.
  int maxControlPoints() const;
  // Largest speed of any control point of any rope, m/s (how still the ropes are).
  double maxSpeed() const;
  // Lowest point of the ropes' centre lines over a dense sample, m (rests at one radius).
  double lowestPoint() const;

 private:
  RestingRopeSceneSettings settings_;
  std::vector<std::unique_ptr<bullet::RopeObject>> ropes_;
};

}  // namespace rope::demos
