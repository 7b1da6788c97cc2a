// SPDX-License-Identifier: MIT
#include "rope/tractrix/length_correction.h"

#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "rope/spline/bspline_basis.h"
#include "rope/spline/gauss_legendre.h"

namespace rope {
namespace {

constexpr double kPi = 3.14159265358979323846;
// The even share of the side weights (header). Measured against an exact follow-the-leader rope (a
// TRX polyline of 2000 segments on the same path) on [B]'s S-bend, a 270° loop, `ropesim tractrix`'s
// figure eight and the sweep circle, weights 1/20 + turning gave the same or a slightly smaller
// largest shape deviation than a uniform scale (w = 1), e.g. 1.54 m against 1.59 m on the loop (5 m
// rope) and 0.92 m against 0.94 m on the figure eight (1.5 m rope); putting everything on the
// last side was worst (2.03 m and 1.17 m).
constexpr double kBaseWeight = 0.05;

// Turning angle pi - theta at interior vertex i (0 = straight), by atan2 as polygon_adaptation.cpp.
double turningAngle(const PointList& points, size_t i) {
  const Vec3 a = points[i] - points[i - 1];
  const Vec3 b = points[i + 1] - points[i];
  return kPi - std::atan2(a.cross(b).norm(), -a.dot(b));
}

// L(c) and dL/dc from the curve's and the offset curve's derivatives at the quadrature points.
void lengthAndSlope(const PointList& curve, const PointList& offset, const std::vector<double>& weight, double c,
                    double& length, double& slope) {
  length = 0.0;
  slope = 0.0;
  for (size_t g = 0; g < curve.size(); ++g) {
    const Vec3 derivative = curve[g] + c * offset[g];
    const double speed = derivative.norm();
    length += weight[g] * speed;
    if (speed > 0.0) slope += weight[g] * derivative.dot(offset[g]) / speed;
  }
}

}  // namespace

LengthCorrectionResult restoreCurveLength(const KnotVector& knots, PointList& points, double targetLength,
                                          const LengthCorrectionOptions& options) {
  LengthCorrectionWorkspace workspace;
  return restoreCurveLength(knots, points, targetLength, options, workspace);
}

LengthCorrectionResult restoreCurveLength(const KnotVector& knots, PointList& points, double targetLength,
                                          const LengthCorrectionOptions& options,
                                          LengthCorrectionWorkspace& workspace) {
  const size_t n = points.size();
  const int d = knots.degree();
  std::vector<double>& sideWeight = workspace.sideWeight;
  PointList& offset = workspace.offset;
  PointList& curveDerivative = workspace.curveDerivative;
  PointList& offsetDerivative = workspace.offsetDerivative;
  std::vector<double>& weight = workspace.weight;

  // Side weights w_i = 1/20 + (tau_i + tau_{i+1}) / pi (header), and the offsets D_i.
  sideWeight.assign(n - 1, kBaseWeight);
  for (size_t i = 1; i + 1 < n; ++i) {
    const double share = turningAngle(points, i) / kPi;
    sideWeight[i - 1] += share;
    sideWeight[i] += share;
  }
  offset.assign(n, Vec3::Zero());
  for (size_t i = 0; i + 1 < n; ++i) offset[i + 1] = offset[i] + sideWeight[i] * (points[i + 1] - points[i]);

  // C'(s) and C_D'(s) at every quadrature point of every non-empty span, with weight half * w_g.
  const GaussRule rule = gaussLegendre(options.gaussPoints);
  curveDerivative.clear();
  offsetDerivative.clear();
  weight.clear();
  BasisValues basis;
  for (int span = d; span < knots.controlPointCount(); ++span) {
    const double a = knots[span];
    const double b = knots[span + 1];
    if (!(b > a)) continue;
    const double half = 0.5 * (b - a);
    const double mid = a + half;
    for (int g = 0; g < rule.count; ++g) {
      evaluateBasis(knots, span, mid + half * rule.nodes[g], 1, basis);
      Vec3 c = Vec3::Zero();
      Vec3 o = Vec3::Zero();
      for (int j = 0; j <= d; ++j) {
        const size_t index = static_cast<size_t>(span - d + j);
        c += basis.d[1][static_cast<size_t>(j)] * points[index];
        o += basis.d[1][static_cast<size_t>(j)] * offset[index];
      }
      curveDerivative.push_back(c);
      offsetDerivative.push_back(o);
      weight.push_back(half * rule.weights[g]);
    }
  }

  LengthCorrectionResult result;
  double length = 0.0;
  double slope = 0.0;
  lengthAndSlope(curveDerivative, offsetDerivative, weight, 0.0, length, slope);
  result.lengthBefore = length;
  result.lengthAfter = length;
  const double tolerance = options.tolerance * targetLength;
  if (std::fabs(length - targetLength) <= tolerance) return result;

  // Newton on the convex L(c): from c = 0 the first step may overshoot, after which the iterates
  // approach the root monotonically.
  double c = 0.0;
  bool converged = false;
  for (int iteration = 1; iteration <= options.maxIterations; ++iteration) {
    if (!(slope > 0.0)) break;  // the offsets cannot change the length (degenerate polygon)
    c -= (length - targetLength) / slope;
    result.iterations = iteration;
    lengthAndSlope(curveDerivative, offsetDerivative, weight, c, length, slope);
    if (std::fabs(length - targetLength) <= tolerance) {
      converged = true;
      break;
    }
  }
  bool sidesKept = true;
  for (double w : sideWeight) sidesKept = sidesKept && 1.0 + c * w >= options.minSideFactor;
  result.scale = c;
  if (!converged || !sidesKept || !std::isfinite(c)) {
    result.feasible = false;
    return result;
  }
  for (size_t i = 1; i < n; ++i) points[i] += c * offset[i];
  result.applied = true;
  result.lengthAfter = length;
  return result;
}

}  // namespace rope
