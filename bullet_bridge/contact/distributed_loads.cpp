// SPDX-License-Identifier: MIT
#include "bullet_bridge/contact/distributed_loads.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

#include "rope/rod/rod.h"
#include "rope/spline/bspline_curve.h"
#include "rope/spline/gauss_legendre.h"

namespace rope::bullet {

namespace {

// Calls sample(s, w) for the Gauss points of every non-empty knot span cut to [s0, s1], with w the
// quadrature weight in parameter units (sum of w over a piece = its parameter length).
template <class Sample>
void forEachSample(const Rod& rod, double s0, double s1, Sample&& sample) {
  const KnotVector& knots = rod.knots();
  const GaussRule rule = gaussLegendre(rod.degree() + 1);
  for (int k = rod.degree(); k < rod.controlPointCount(); ++k) {
    const double a = std::max(knots[k], s0);
    const double b = std::min(knots[k + 1], s1);
    if (!(b > a)) continue;
    const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
    for (int q = 0; q < rule.count; ++q) sample(mid + half * rule.nodes[q], half * rule.weights[q]);
  }
}

}  // namespace

void queueDistributedForce(Rod& rod, double s0, double s1, const Vec3& forcePerLength) {
  const Eigen::Matrix3d zero = Eigen::Matrix3d::Zero();
  forEachSample(rod, s0, s1, [&](double s, double weight) {
    const double restMetric = evaluateCurve(rod.knots(), rod.restControlPoints(), s).firstDerivative.norm();
    rod.addSpringSample(s, (weight * restMetric) * forcePerLength, zero, zero);
  });
}

void queueDrag(Rod& rod, const DragLaw& law) {
  if (!law.active()) return;
  const Eigen::Matrix3d zero = Eigen::Matrix3d::Zero();
  forEachSample(rod, rod.beginParameter(), rod.endParameter(), [&](double s, double weight) {
    const Vec3 derivative = evaluateCurve(rod.knots(), rod.controlPoints(), s).firstDerivative;
    const double metric = derivative.norm();
    if (!(metric > 0.0)) return;  // a degenerate point has no length to drag
    const Vec3 t = derivative / metric;
    const Vec3 w = rod.velocity(s) - law.wind;
    const double along = w.dot(t);
    const Vec3 wn = w - along * t;
    const double normalSpeed = wn.norm();
    // q = -c_n |w_n| w_n - c_t |w.t| (w.t) t, and D = -dq/dw (header comment).
    Vec3 q = -law.normal * normalSpeed * wn - law.tangential * std::abs(along) * along * t;
    Eigen::Matrix3d d = (2.0 * law.tangential * std::abs(along)) * (t * t.transpose());
    if (normalSpeed > 0.0) {
      const Eigen::Matrix3d projector = Eigen::Matrix3d::Identity() - t * t.transpose();
      d += law.normal * (normalSpeed * projector + (wn * wn.transpose()) / normalSpeed);
    }
    const double length = weight * metric;  // m of current rope this sample stands for
    rod.addSpringSample(s, length * q, zero, length * d);
  });
}

}  // namespace rope::bullet
