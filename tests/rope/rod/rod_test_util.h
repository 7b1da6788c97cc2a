// SPDX-License-Identifier: MIT
#pragma once
// Helpers shared by the rod tests.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "rope/common/error.h"
#include "rope/rod/rod.h"

namespace rope::test {

// Angular momentum about the origin, integral of mu C(s) x V(s) l0'(s) ds, kg m^2/s, through the
// rod's own mass blocks: sum_j sum_ab M^j_ab q_a x v_b, exact for any rest curve.
inline Vec3 angularMomentum(const Rod& rod) {
  const RodIntegrals& integrals = rod.integrals();
  const int local = rod.degree() + 1;
  Vec3 sum = Vec3::Zero();
  for (int j = 0; j < integrals.spanCount(); ++j) {
    const SpanView span = integrals.span(j);
    for (int a = 0; a < local; ++a)
      for (int b = 0; b < local; ++b)
        sum += span.mass[a * local + b] *
               rod.controlPoints()[static_cast<size_t>(j + a)].cross(rod.velocities()[static_cast<size_t>(j + b)]);
  }
  return sum;
}


// Everything a step or an edit may change, for "object unchanged" and bitwise twin checks.
struct RodSnapshot {
  std::vector<double> knots;
  PointList points, velocities, rest;
  std::vector<Pin> pins;
  explicit RodSnapshot(const Rod& rod)
      : knots(rod.knots().values()),
        points(rod.controlPoints()),
        velocities(rod.velocities()),
        rest(rod.restControlPoints()),
        pins(rod.pins()) {}
};

inline bool bitwiseEqual(const PointList& a, const PointList& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k)
      if (a[i][k] != b[i][k]) return false;
  return true;
}

inline ::testing::AssertionResult sameState(const RodSnapshot& a, const RodSnapshot& b) {
  if (a.knots != b.knots) return ::testing::AssertionFailure() << "knots differ";
  if (!bitwiseEqual(a.points, b.points)) return ::testing::AssertionFailure() << "points differ";
  if (!bitwiseEqual(a.velocities, b.velocities)) return ::testing::AssertionFailure() << "velocities differ";
  if (!bitwiseEqual(a.rest, b.rest)) return ::testing::AssertionFailure() << "rest points differ";
  if (a.pins.size() != b.pins.size()) return ::testing::AssertionFailure() << "pin count differs";
  for (size_t i = 0; i < a.pins.size(); ++i) {
    if (a.pins[i].id != b.pins[i].id || a.pins[i].parameter != b.pins[i].parameter ||
        a.pins[i].target != b.pins[i].target || a.pins[i].direction != b.pins[i].direction)
      return ::testing::AssertionFailure() << "pin " << i << " differs";
  }
  return ::testing::AssertionSuccess();
}

// A bad call on a live rod and the parameter its InvalidArgument must name.
struct RodCall {
  const char* parameter;
  std::function<void(Rod&)> call;
};

// Every call must throw InvalidArgument naming its parameter and leave `rod` bitwise as it was.
inline void expectEachCallRejected(Rod& rod, const std::vector<RodCall>& calls) {
  const RodSnapshot before(rod);
  for (const RodCall& c : calls) {
    try {
      c.call(rod);
      ADD_FAILURE() << "no exception for " << c.parameter;
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.parameter(), c.parameter) << e.what();
    }
    EXPECT_TRUE(sameState(before, RodSnapshot(rod))) << c.parameter;
  }
}

// Straight rest curve along x at the Greville abscissae (l0' = 1): the energy tests' reference rod.
inline PointList straightRest(const KnotVector& knots) {
  PointList rest;
  for (int i = 0; i < knots.controlPointCount(); ++i) {
    double sum = 0.0;
    for (int k = 1; k <= knots.degree(); ++k) sum += knots[i + k];
    rest.emplace_back(sum / knots.degree(), 0.0, 0.0);
  }
  return rest;
}

// Lowest point of the curve along -gravity (y), sampled finely.
inline double lowestY(const Rod& rod, int samples = 4000) {
  double lowest = rod.position(rod.beginParameter()).y();
  for (int i = 0; i <= samples; ++i) {
    const double s = rod.beginParameter() + (rod.endParameter() - rod.beginParameter()) * i / samples;
    lowest = std::min(lowest, rod.position(s).y());
  }
  return lowest;
}

// Strain of the rod's Green–Lagrange law ([A] eq. 11: E = (EA/8) int (gamma^2 - 1)^2, so the tension
// is T = EA eps (1 + eps)(1 + eps/2)) under tension T (N), by Newton's method from T / EA.
inline double greenLagrangeStrain(double tension, double axialStiffness) {
  const double target = tension / axialStiffness;
  double eps = target;
  for (int i = 0; i < 50; ++i) {
    const double f = eps * (1.0 + eps) * (1.0 + 0.5 * eps) - target;
    const double df = 1.0 + 3.0 * eps + 1.5 * eps * eps;
    eps -= f / df;
  }
  return eps;
}

// Static strain of a rope of rest length L (m) and weight w (N/m) hanging from its top with a load W
// (N) at its bottom, exact for the Green–Lagrange law: the tension at rest arclength p above the load
// is W + w p. `mean` is the rope's relative elongation (length / L - 1, the integral of the strain by
// Simpson's rule, error ~1e-16 here), `top` the strain where the tension is largest (W + w L).
struct HangingStrain {
  double mean = 0.0;
  double top = 0.0;
};
inline HangingStrain hangingStrain(double load, double weightPerLength, double length, double axialStiffness) {
  const int n = 1000;  // even
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double weight = (i == 0 || i == n) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    sum += weight * greenLagrangeStrain(load + weightPerLength * length * i / n, axialStiffness);
  }
  return {sum / (3.0 * n), greenLagrangeStrain(load + weightPerLength * length, axialStiffness)};
}

}  // namespace rope::test
