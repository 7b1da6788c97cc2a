#pragma once
// Helpers shared by the rod tests.

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "rope/rod/rod.h"

namespace rope::test {

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

// Lowest point of the curve along -gravity (y), sampled finely.
inline double lowestY(const Rod& rod, int samples = 4000) {
  double lowest = rod.position(rod.beginParameter()).y();
  for (int i = 0; i <= samples; ++i) {
    const double s = rod.beginParameter() + (rod.endParameter() - rod.beginParameter()) * i / samples;
    lowest = std::min(lowest, rod.position(s).y());
  }
  return lowest;
}

}  // namespace rope::test
