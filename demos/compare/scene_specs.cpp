// SPDX-License-Identifier: MIT
#include "demos/compare/scene_specs.h"

#include <algorithm>
#include <cmath>

namespace rope::compare {

demos::HangSceneSettings CatenarySpec::flexible() {
  demos::HangSceneSettings hang;
  hang.rod.bendingStiffness = 0.0;
  return hang;
}

double CatenarySpec::analyticSag() const { return demos::HangScene(hang).analyticSag(); }

double CatenarySpec::pinDistance(double t) const {
  if (hang.closeTime <= 0.0 || t >= hang.closeTime) return hang.span;
  const double u = t / hang.closeTime;
  return hang.ropeLength + (hang.span - hang.ropeLength) * u * u * (3.0 - 2.0 * u);
}

demos::CraneSceneSettings HeavyLoadSpec::defaults() {
  demos::CraneSceneSettings crane;
  crane.liftStart = 1e9;  // never lift: the scene is the static load case
  return crane;
}

double HeavyLoadSpec::expectedStrain() const {
  RodSettings rod = crane.rod;
  rod.restLength = crane.ropeLength;
  return crane.boxMass * rod.gravity.norm() / rod.axialStiffness();
}

DrapeSpec DrapeSpec::thinBar() {
  DrapeSpec spec;
  spec.drape = demos::DrapeSceneSettings::thinBar();
  spec.seconds = 2.5;  // the rope falls 1 m (0.45 s) and swings; 2 s on the bar
  return spec;
}

DrapeSpec DrapeSpec::box() {
  DrapeSpec spec;
  spec.seconds = 2.0;
  return spec;
}

// Mirrors DrapeScene's obstacle placement.
Eigen::Vector3d DrapeSpec::obstacleCentre() const {
  if (drape.obstacle == demos::DrapeSceneSettings::Obstacle::kBox) return {0.0, 0.5 * drape.obstacleTop, 0.0};
  return {0.0, drape.obstacleTop - 0.5 * drape.barThickness, 0.0};
}

Eigen::Vector3d DrapeSpec::obstacleHalfExtents() const {
  if (drape.obstacle == demos::DrapeSceneSettings::Obstacle::kBox) return {0.6, 0.5 * drape.obstacleTop, 0.3};
  return {0.5 * drape.barThickness, 0.5 * drape.barThickness, 0.3};
}

double DrapeSpec::penetration(const Eigen::Vector3d& point) const {
  const Eigen::Vector3d local = (point - obstacleCentre()).cwiseAbs() - obstacleHalfExtents();
  // Signed distance to a box: outside part plus (negative) inside part.
  const double outside = local.cwiseMax(0.0).norm();
  const double inside = std::min(local.maxCoeff(), 0.0);
  return std::max(0.0, drape.rod.radius - (outside + inside));
}

}  // namespace rope::compare
