// SPDX-License-Identifier: MIT
#include "demos/scenes/arc_path.h"

#include <algorithm>
#include <cmath>

#include "rope/common/error.h"

namespace rope::demos {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

Vec3 ArcPath::at(double s) const {
  requireNonNegative("s", s);
  Vec3 p = Vec3::Zero();
  double heading = headingStart;
  auto run = [&](double length) {
    const double l = std::min(length, s);
    p += l * Vec3(std::cos(heading), std::sin(heading), 0.0);
    s -= l;
  };
  auto arc = [&](double turn) {
    const double l = std::min(radius * std::fabs(turn), s);
    const double sign = turn > 0 ? 1.0 : -1.0;
    const Vec3 centre = p + sign * radius * Vec3(-std::sin(heading), std::cos(heading), 0.0);
    const double start = std::atan2(p.y() - centre.y(), p.x() - centre.x());
    const double end = start + sign * l / radius;
    p = centre + radius * Vec3(std::cos(end), std::sin(end), 0.0);
    heading += sign * l / radius;
    s -= l;
  };
  run(straight);
  if (s > 0) arc(firstTurn);
  if (s > 0) arc(secondTurn);
  if (s > 0) run(s);
  return p;
}

ArcPath sBendPath() { return ArcPath{0.0, 1.0, 1.2, 0.5 * kPi, -kPi}; }
ArcPath loopPath() { return ArcPath{0.5 * kPi, 1.0, 1.5, 1.5 * kPi, -kPi}; }

}  // namespace rope::demos
