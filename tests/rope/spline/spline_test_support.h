// SPDX-License-Identifier: MIT
#pragma once
// Shared helpers for the B-spline tests: random non-uniform curves (clamped and unclamped, degree
// 1..5, repeated knots), an independent Cox–de Boor reference, and size measures for tolerances.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "rope/common/error.h"
#include "rope/spline/bspline_curve.h"
#include "rope/spline/knot_vector.h"

namespace rope::test {

// Random knot vector: spans of random length in [0.05, 1.05) (some interior knots repeated up to
// maxInteriorMultiplicity times), clamped ends (d+1 equal knots) or all-distinct unclamped ends.
inline KnotVector randomKnots(std::mt19937& rng, int degree, int controlPoints, bool clamped,
                              int maxInteriorMultiplicity) {
  std::uniform_real_distribution<double> gap(0.05, 1.05);
  std::uniform_int_distribution<int> repeat(1, std::max(1, maxInteriorMultiplicity));
  std::uniform_real_distribution<double> start(-3.0, 3.0);
  const int total = controlPoints + degree + 1;
  std::vector<double> knots;
  double s = start(rng);
  if (clamped) {
    for (int i = 0; i <= degree; ++i) knots.push_back(s);
  }
  // Interior (or, unclamped, all) knots; the last d+1 are filled below.
  while (static_cast<int>(knots.size()) < total - (clamped ? degree + 1 : 0)) {
    s += gap(rng);
    const int m = std::min(repeat(rng), total - (clamped ? degree + 1 : 0) - static_cast<int>(knots.size()));
    for (int i = 0; i < m; ++i) knots.push_back(s);
  }
  if (clamped) {
    s += gap(rng);
    for (int i = 0; i <= degree; ++i) knots.push_back(s);
  }
  // Unclamped vectors built with repeats could end with an empty valid range or too long a run:
  // retry in that (rare) case.
  try {
    return KnotVector(degree, knots);
  } catch (const InvalidArgument&) {
    return randomKnots(rng, degree, controlPoints, clamped, 1);
  }
}

// A random curve of the given degree with d+1..d+12 control points spread over a box whose size
// varies over four orders of magnitude, offset from the origin.
inline BSplineCurve randomCurve(std::mt19937& rng, int degree, bool clamped, int maxInteriorMultiplicity) {
  std::uniform_int_distribution<int> extra(0, 11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> exponent(-2.0, 2.0);
  const int n = degree + 1 + extra(rng);
  const double scale = std::pow(10.0, exponent(rng));
  const Vec3 offset(5.0 * unit(rng), 5.0 * unit(rng), 5.0 * unit(rng));
  PointList points;
  for (int i = 0; i < n; ++i) points.push_back(offset + scale * Vec3(unit(rng), unit(rng), unit(rng)));
  return BSplineCurve(randomKnots(rng, degree, n, clamped, maxInteriorMultiplicity), points);
}

// A rope-like curve: control points on a helix at the Greville abscissae, plus noise of 1e-3 of
// the radius, on random non-uniform knots. Removing a knot moves it a little, as in simulation.
inline BSplineCurve smoothCurve(std::mt19937& rng, int degree, bool clamped) {
  std::uniform_int_distribution<int> extra(1, 12);
  std::uniform_real_distribution<double> noise(-1e-3, 1e-3);
  std::uniform_real_distribution<double> radius(0.05, 5.0);
  const int n = degree + 1 + extra(rng);
  const KnotVector knots = test::randomKnots(rng, degree, n, clamped, degree);
  const double r = radius(rng);
  PointList points;
  for (int i = 0; i < n; ++i) {
    double greville = 0.0;
    for (int j = 1; j <= degree; ++j) greville += knots[i + j] / degree;
    points.push_back(r * Vec3(std::cos(greville) + noise(rng), std::sin(greville) + noise(rng), 0.3 * greville + noise(rng)));
  }
  return BSplineCurve(knots, points);
}

// Diagonal of the control points' bounding box: the convex hull contains the curve, so this is
// the curve's size scale (metres) for relative tolerances.
inline double sizeOf(const PointList& points) {
  Vec3 lo = points.front();
  Vec3 hi = points.front();
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

// Shortest non-empty knot span inside the valid range.
inline double shortestSpan(const KnotVector& knots) {
  double shortest = knots.validEnd() - knots.validBegin();
  for (int k = knots.degree(); k < knots.controlPointCount(); ++k) {
    const double h = knots[k + 1] - knots[k];
    if (h > 0.0) shortest = std::min(shortest, h);
  }
  return shortest;
}

// count uniformly random parameters in the valid range plus every knot in it and both ends.
inline std::vector<double> sampleParameters(std::mt19937& rng, const KnotVector& knots, int count) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> s;
  const double a = knots.validBegin();
  const double b = knots.validEnd();
  for (int i = 0; i < count; ++i) s.push_back(std::min(b, a + (b - a) * u(rng)));
  for (double t : knots.values()) {
    if (t >= a && t <= b) s.push_back(t);
  }
  s.push_back(a);
  s.push_back(b);
  return s;
}

// The Cox–de Boor definition, recursively, with 0/0 = 0 and half-open supports; the last function
// is closed at validEnd so that the reference matches the library's span convention there.
inline double referenceBasis(const std::vector<double>& t, int i, int p, double s, double validEnd) {
  if (p == 0) {
    // s == validEnd belongs to the last non-empty span ending there (not to the one starting there).
    if (s == validEnd) {
      return t[static_cast<size_t>(i + 1)] == validEnd && t[static_cast<size_t>(i)] < validEnd ? 1.0 : 0.0;
    }
    return t[static_cast<size_t>(i)] <= s && s < t[static_cast<size_t>(i + 1)] ? 1.0 : 0.0;
  }
  double value = 0.0;
  const double left = t[static_cast<size_t>(i + p)] - t[static_cast<size_t>(i)];
  const double right = t[static_cast<size_t>(i + p + 1)] - t[static_cast<size_t>(i + 1)];
  if (left > 0.0) value += (s - t[static_cast<size_t>(i)]) / left * referenceBasis(t, i, p - 1, s, validEnd);
  if (right > 0.0) {
    value += (t[static_cast<size_t>(i + p + 1)] - s) / right * referenceBasis(t, i + 1, p - 1, s, validEnd);
  }
  return value;
}

// Runs f and expects InvalidArgument naming exactly `parameter` and containing `value` in its message.
template <class F>
void expectInvalid(F&& f, const std::string& parameter, const std::string& value) {
  try {
    f();
    ADD_FAILURE() << "expected InvalidArgument for " << parameter;
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.parameter(), parameter) << e.what();
    EXPECT_NE(std::string(e.what()).find(value), std::string::npos) << e.what() << " lacks " << value;
  }
}

}  // namespace rope::test
