// SPDX-License-Identifier: MIT
#pragma once
// The physical scenes every engine runs, taken from SplineRope's own scene builders (so the
// SplineRope side is exactly the demo scene) plus the quantities the peers need to match them.

#include <Eigen/Core>

#include <algorithm>
#include <map>
#include <string>

#include "demos/scenes/crane_scene.h"
#include "demos/scenes/drape_scene.h"
#include "demos/scenes/hang_scene.h"

namespace rope::compare {

// (1) catenary: both ends pinned, drawn together to span over closeTime, then settle. Sag is
// averaged over the last averagingWindow seconds (the ropes are lightly damped, not at rest).
struct CatenarySpec {
  // The demo scene's rope (1.25 m over 1 m, r = 1 cm, E = 2e8 Pa) without bending stiffness: neither
  // peer has any, nor does the analytic catenary (with the scene's solid-rod EI = 1.6 N m^2 the sag
  // was about 0.5 % off it).
  demos::HangSceneSettings hang = flexible();
  static demos::HangSceneSettings flexible();
  double seconds = 8.0;           // s simulated (pins closed after 1 s)
  double averagingWindow = 2.0;   // s
  double analyticSag() const;     // m, inextensible catenary
  double pinDistance(double t) const;  // m, HangScene's smoothstep schedule
};

// (2) heavy load: the crane scene without the lift (10 kg on 1 m of 0.01 kg/m rope, EA = 25.1 kN).
// Strain = rope length / rest length - 1, averaged over the last averagingWindow seconds.
struct HeavyLoadSpec {
  demos::CraneSceneSettings crane = defaults();
  double seconds = 4.0;
  double averagingWindow = 1.0;
  double expectedStrain() const;  // W / (EA) of the box's weight
  static demos::CraneSceneSettings defaults();
};

// (3) thin bar (DrapeSceneSettings::thinBar()) and (4) drape over a box (the default drape scene).
struct DrapeSpec {
  demos::DrapeSceneSettings drape;
  double seconds = 2.5;
  double restingWindow = 0.5;  // s at the end over which the resting penetration is taken
  static DrapeSpec thinBar();
  static DrapeSpec box();
  // The obstacle as a box: centre and half extents, m.
  Eigen::Vector3d obstacleCentre() const;
  Eigen::Vector3d obstacleHalfExtents() const;
  // How far a sphere of the rope's radius at `point` reaches into the obstacle, m (0 if clear).
  double penetration(const Eigen::Vector3d& point) const;
};

// What every engine's drape run measures of its rope: the deepest penetration into the obstacle
// over the whole run and over its last restingWindow, each state taken at its deepest sample point.
class DrapePenetration {
 public:
  DrapePenetration(const DrapeSpec& spec, double duration) : spec_(spec), duration_(duration) {}
  // The state at time t (s); forEachPoint(visit) calls visit with each sample point of the rope (m).
  template <class ForEachPoint>
  void sample(double t, ForEachPoint&& forEachPoint) {
    double deepest = 0.0;
    forEachPoint([&](const Eigen::Vector3d& point) { deepest = std::max(deepest, spec_.penetration(point)); });
    max_ = std::max(max_, deepest);
    if (t > duration_ - spec_.restingWindow) resting_ = std::max(resting_, deepest);
  }
  // max_penetration_m and resting_penetration_m, m.
  void record(std::map<std::string, double>& metrics) const {
    metrics["max_penetration_m"] = max_;
    metrics["resting_penetration_m"] = resting_;
  }

 private:
  const DrapeSpec& spec_;
  double duration_;
  double max_ = 0.0, resting_ = 0.0;
};

// (5) scaling: the catenary scene at a fixed resolution (no adaptivity), time per step only.
struct ScalingSpec {
  CatenarySpec catenary;
  int maxSteps = 240;          // steps timed (after warmupSteps)
  int warmupSteps = 24;
  double wallBudget = 6.0;     // s per trial; a slow engine is timed over fewer steps (>= 2)
};

}  // namespace rope::compare
