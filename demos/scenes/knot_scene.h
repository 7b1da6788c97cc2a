// SPDX-License-Identifier: MIT
#pragma once
// "knot": knot tying ([A] §5.2) in a Bullet world. A rope is laid out as a loose overhand knot (a
// trefoil cut open at one lobe, its two ends led out along -z and +z as tails) and held by two
// kinematic grippers (Bullet bodies that move with the rope's end pins) above a ground plane. Then
//   kGravity: the grippers stay put and the knot tightens under its own weight, as in the paper;
//   kPull:    after settleTime the grippers pull the ends apart at up to pullSpeed, force-controlled:
//             each moves at a speed proportional to how far the strain at its end is below
//             pullTension / EA (backing off above it), so the knot is drawn tight and then held at
//             that tension (a robot pulling with force control).
// Self-contact (contact/rope_rope_contact.h) keeps the rope out of itself; its contact points get knots, so
// the knot vector ends up dense in the knot and sparse along the tails.

#include <memory>

#include "bullet_bridge/rope_object.h"
#include "demos/scenes/world_scene.h"

namespace rope::demos {

struct KnotSceneSettings {
  enum class Tightening { kGravity, kPull };
  Tightening tightening = Tightening::kPull;
  double loopScale = 0.02;     // m, > 0: scale R of the trefoil (the loose knot is about 6R across)
  double endGap = 0.25;        // rad, in (0, 1): the trefoil is cut open over 2 endGap of its parameter
  double tailLength = 0.3;     // m, > 0: each tail, from the knot to its gripper
  double height = 0.5;         // m, > 0: height of the tails above the ground
  double settleTime = 0.5;     // s, >= 0: kPull holds the grippers this long before pulling
  double pullSpeed = 0.15;     // m/s, > 0: top speed of each gripper (kPull)
  double pullTension = 3.0;    // N, > 0: end tension the pull settles at (kPull)
  double timeStep = 1.0 / 240.0;  // s, > 0
  RodSettings rod = defaultRod();
  bullet::BulletRopeSettings bridge = defaultBridge();

  // 5 mm radius limp nylon cord (E = 1e8 Pa, EI = 1e-4 N m^2), damped; up to 160 control points.
  static RodSettings defaultRod();
  // The default contact law (1e4 N/m: a knot pulled at 3 N sinks into itself by about a millimetre)
  // and speculative margin, with friction 0.3 at every contact (sqrt(0.3) on each surface: Bullet's product).
  static bullet::BulletRopeSettings defaultBridge();
  static KnotSceneSettings gravity();  // kGravity, with a heavy cord (0.3 kg/m) whose weight ties the knot
};

// The loose overhand knot as a polyline (m), starting at the -z tail's end: a trefoil of scale
// loopScale in a vertical plane (x, y), cut open at its top lobe, plus the two tails. Throws
// InvalidArgument naming the field for bad settings.
PointList overhandKnotPolyline(const KnotSceneSettings& settings);

// Where the knot is: the stretch of rope between the smallest and the largest parameter of the
// active self-contacts (empty when there are none).
struct KnotRegion {
  bool found = false;
  double begin = 0.0, end = 0.0;  // curve parameters
  double length = 0.0;            // m, curve length of the stretch
  double extent = 0.0;            // m, largest edge of its axis-aligned bounding box
};
KnotRegion knotRegion(const bullet::RopeObject& rope, const bullet::ContactReport& report);

class KnotScene : public WorldScene {
 public:
  explicit KnotScene(const KnotSceneSettings& settings);

  StepMeasurements step() override;
  StepMeasurements measure() const override;
  void draw(render::Scene& scene) const override;
  std::optional<render::Camera> camera() const override;

  const bullet::RopeObject& rope() const { return *rope_; }
  KnotRegion knot() const { return knotRegion(*rope_, physics_.ropes().lastReport()); }
  // Distance between the two grippers' pins, m.
  double endSeparation() const;
  // Strain at the two ends (just inside the pins), the pull's feedback.
  double endStrain() const;

 private:
  void moveGrippers(double h);

  KnotSceneSettings settings_;
  std::unique_ptr<bullet::RopeObject> rope_;
  btRigidBody* grippers_[2] = {nullptr, nullptr};
  int pins_[2] = {0, 0};
  btVector3 pinPoints_[2];
};

}  // namespace rope::demos
