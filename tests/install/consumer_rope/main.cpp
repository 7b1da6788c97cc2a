// SPDX-License-Identifier: MIT
// Uses SplineRope::rope alone (Eigen only): a rope pinned at both ends, laid straight and 20 %
// compressed between supports 1 m apart, falls into the catenary (docs/method.md §8); a tractrix rope
// dragged by its leading end follows it and keeps its length within 10 % (§13–§14).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rope/rod/rod.h"
#include "rope/tractrix/tractrix_rope.h"

namespace {

// Sag of the inextensible catenary of length L over the span D: L = 2a sinh(D / 2a), a by bisection.
double catenarySag(double span, double length) {
  double lo = 1e-3, hi = 1e3;
  for (int i = 0; i < 200; ++i) {
    const double a = 0.5 * (lo + hi);
    (2.0 * a * std::sinh(span / (2.0 * a)) > length ? lo : hi) = a;
  }
  const double a = 0.5 * (lo + hi);
  return a * (std::cosh(span / (2.0 * a)) - 1.0);
}

}  // namespace

int main() {
  rope::RodSettings settings;
  settings.restLength = 1.25;       // m, between supports 1 m apart
  settings.linearDensity = 0.1;     // kg/m
  settings.bendingStiffness = 0.0;  // a catenary has none
  settings.massDamping = 3.0;       // 1/s, to settle
  settings.initialControlPoints = 12;
  settings.maxControlPoints = 16;
  rope::Rod rod = rope::Rod::fromSegment(settings, {-0.5, 0, 0}, {0.5, 0, 0});
  rod.pin(rod.beginParameter());
  rod.pin(rod.endParameter());
  for (int i = 0; i < 12 * 240; ++i) {
    const rope::StepReport report = rod.step(1.0 / 240.0);
    if (!report.ok) {
      std::printf("step %d failed: %s\n", i, report.failure);
      return 1;
    }
  }
  double lowest = 0.0;
  for (int i = 0; i <= 400; ++i) lowest = std::min(lowest, rod.position(rod.endParameter() * i / 400.0).y());
  const double sag = -lowest;
  const double expected = catenarySag(1.0, 1.25);

  rope::TractrixRope hose({{0, 0, 0}, {5, 0, 0}});  // 5 m, leading end at the origin
  rope::Vec3 target = rope::Vec3::Zero();
  for (int i = 1; i <= 10; ++i) {
    target = rope::Vec3(-0.5 * i, 0.3 * i, 0);
    hose.moveLeadingEnd(target);
  }

  std::printf("catenary sag %.5f m (analytic %.5f m), %d control points; tractrix length error %.4f\n", sag,
              expected, rod.controlPointCount(), hose.lengthError());
  const bool ok = std::abs(sag - expected) < 0.01 * expected && rod.controlPointCount() <= 16 &&
                  (hose.leadingEnd() - target).norm() < 1e-12 && std::abs(hose.lengthError()) < 0.1;
  return ok ? 0 : 1;
}
