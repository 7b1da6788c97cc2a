// SPDX-License-Identifier: MIT
#pragma once
// "capstan": a rope wrapped over a fixed horizontal obstacle by an angle theta and loaded at its two
// ends by a light and a heavy body, to check the capstan (Euler–Eytelwein) law: a perfectly flexible,
// weightless rope on a rough round support holds while the tension ratio stays below exp(mu theta)
// and slips beyond it (T_heavy / T_light = exp(mu theta) at the limit).
//
// The obstacle's axis runs along z through (0, height, 0); it is either
//   kCylinder: a static btCylinderShapeZ of radius cylinderRadius (rope–body friction), or
//   kTautRope: a second rope stretched along z between two point attachments at tautTension
//              (rope–rope friction; its contact radius is the sum of the two ropes' radii).
// The rope starts already wrapped, symmetric about the top of the obstacle: the arc phi in
// [-theta/2, theta/2] (phi measured from +y towards +x) on the circle of radius
// wrapRadius = obstacle radius + rope radius, with a helix pitch along z (so that a full turn does
// not overlap itself), plus two straight strands of strandLength leaving along the arc's end
// tangents (in the x-y plane). Each strand ends in a small dynamic sphere attached to the rope's end
// (RopeObject::attachToBody at the sphere's centre, so the load exerts no torque). Each sphere is a
// "hanging mass over an ideal pulley": mass load / 9.81 m/s^2 and its own gravity (world gravity
// switched off for it) of 9.81 m/s^2 along its strand, away from the obstacle, ramped up linearly
// over loadRampTime so the rope is loaded quasi-statically. For theta = pi both strands hang
// straight down and this is an ordinary pair of hanging masses; other angles need the pulley.
//
// The rope's own gravity is zero (the law is for a weightless rope; its weight would add to the end
// tensions) and its bending stiffness is zero (the law is for a perfectly flexible rope: bending
// would add concentrated contact forces where the rope meets and leaves the support, i.e. extra
// friction). The begin end carries the light load, the end end the heavy load.
//
// Helix: with pitch p, the rope on the support is a helix of angle alpha, tan(alpha) = p / (2 pi r_w),
// for which the law becomes exp(mu theta cos(alpha)); the derived pitch is zero up to a half turn and
// 2.5 rope diameters beyond, where cos(alpha) = 0.9983 on the default 5 cm cylinder (the limit
// moves by 1.1 % at mu theta = 2 pi, well inside a +-10 % test band).

#include <memory>

#include "bullet_bridge/rope_object.h"
#include "demos/scenes/world_scene.h"

namespace rope::demos {

struct CapstanSceneSettings {
  static constexpr double kDerived = -1.0;
  enum class Obstacle { kCylinder, kTautRope };
  Obstacle obstacle = Obstacle::kCylinder;
  double wrapAngle = 3.14159265358979323846;  // theta, rad, in (0, 4 pi]
  double friction = 0.3;         // mu, >= 0: the contact's coefficient (the rope's friction; the cylinder and the taut rope carry 1)
  double loadRatio = 1.0;        // T_heavy / T_light, >= 1
  double heavyLoad = 10.0;       // N, > 0: the heavy end's load; the light one is heavyLoad / loadRatio
  double cylinderRadius = 0.05;  // m, > 0 (kCylinder)
  double cylinderHalfLength = 0.1;  // m, > 0, along z (kCylinder)
  double tautSpan = 0.4;         // m, > 0: distance between the taut rope's attachments (kTautRope)
  double tautTension = 200.0;    // N, > 0: the taut rope's tension before the load (kTautRope)
  double height = 1.0;           // m: height of the obstacle's axis
  double strandLength = 0.3;     // m, > 0: each straight strand, from the support to its load
  double helixPitch = kDerived;  // m of z per full turn, >= 0, or kDerived (see above)
  double loadRampTime = 0.2;     // s, >= 0: the loads grow linearly from zero over this time
  double timeStep = 1.0 / 240.0; // s, > 0
  RodSettings rod = defaultRod();
  bullet::BulletRopeSettings bridge;  // friction is overwritten by `friction` above

  // 5 mm radius limp cord (E = 1e8 Pa: EA = 7.85 kN, so 10 N stretches it by 0.13 %), perfectly
  // flexible (EI = 0) and weightless (gravity 0), on the rope's default damping (none).
  static RodSettings defaultRod();
  double effectiveHelixPitch() const;
  // The contact radius of the rope on the support (centre line to axis), m.
  double wrapRadius() const;
  // exp(mu theta): the load ratio at which the law puts the onset of slip.
  double capstanLimit() const;
};

// The wrapped rope's initial centre line (m), from the light end to the heavy end: strand, arc
// (a point every 5 degrees), strand. Throws InvalidArgument naming the field for bad settings.
PointList capstanPolyline(const CapstanSceneSettings& settings);

class CapstanScene : public WorldScene {
 public:
  // Throws InvalidArgument naming the field for bad settings.
  explicit CapstanScene(const CapstanSceneSettings& settings);
  ~CapstanScene() override;

  StepMeasurements step() override;
  StepMeasurements measure() const override;
  void draw(render::Scene& scene) const override;
  std::optional<render::Camera> camera() const override;

  const CapstanSceneSettings& settings() const { return settings_; }
  const bullet::RopeObject& rope() const { return *rope_; }
  const bullet::RopeObject* tautRope() const { return taut_.get(); }
  // Distance the heavy load has moved along its pull direction since the start, m (> 0: the rope
  // slides towards the heavy side), and its speed along that direction, m/s.
  double heavyTravel() const;
  double heavySpeed() const;
  // Same for the light load along its own pull direction (it moves backwards, < 0, when the rope slips).
  double lightTravel() const;
  // How far the rope has slid over its support towards the heavy side since the start, m: half the
  // difference of the two loads' travels, so that a support that itself moves (the taut rope sags and
  // swings under the load, carrying both loads with it) does not count as slip.
  double ropeSlip() const { return 0.5 * (heavyTravel() - lightTravel()); }

 private:
  void applyLoads(double t);  // the loads' ramp at time t, s

  CapstanSceneSettings settings_;
  std::unique_ptr<bullet::RopeObject> taut_;
  std::unique_ptr<bullet::RopeObject> rope_;
  btRigidBody* loads_[2] = {nullptr, nullptr};  // light (rope begin), heavy (rope end)
  btVector3 pullDirections_[2];                 // unit, away from the support along each strand
  btVector3 loadGravity_[2];                    // m/s^2: each load's full gravity, along its strand
  btVector3 startPositions_[2];
  double loadForces_[2] = {0.0, 0.0};           // N
  long steps_ = 0;
};

}  // namespace rope::demos
