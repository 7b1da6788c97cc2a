// SPDX-License-Identifier: MIT
#include "support/elastica.h"

#include <cmath>

namespace rope::test {

ElasticaTip elastica(double length, double bendingStiffness, double tipLoad, double weightPerLength) {
  const int steps = 4000;
  const double ds = length / steps;
  // State: theta, theta', x, y. Returns theta'(L) and the tip.
  auto shoot = [&](double curvature0, ElasticaTip& tip) {
    double state[4] = {0.0, curvature0, 0.0, 0.0};
    auto derivative = [&](double s, const double* u, double* du) {
      du[0] = u[1];
      du[1] = (tipLoad + weightPerLength * (length - s)) * std::cos(u[0]) / bendingStiffness;
      du[2] = std::cos(u[0]);
      du[3] = std::sin(u[0]);
    };
    for (int i = 0; i < steps; ++i) {
      const double s = i * ds;
      double k1[4], k2[4], k3[4], k4[4], u[4];
      derivative(s, state, k1);
      for (int c = 0; c < 4; ++c) u[c] = state[c] + 0.5 * ds * k1[c];
      derivative(s + 0.5 * ds, u, k2);
      for (int c = 0; c < 4; ++c) u[c] = state[c] + 0.5 * ds * k2[c];
      derivative(s + 0.5 * ds, u, k3);
      for (int c = 0; c < 4; ++c) u[c] = state[c] + ds * k3[c];
      derivative(s + ds, u, k4);
      for (int c = 0; c < 4; ++c) state[c] += ds / 6.0 * (k1[c] + 2 * k2[c] + 2 * k3[c] + k4[c]);
    }
    tip.x = state[2];
    tip.y = state[3];
    return state[1];
  };
  // |EI theta'(0)| is the root moment, at most P L + w L^2 / 2 (the undeflected lever arms).
  double lo = -(tipLoad * length + 0.5 * weightPerLength * length * length) / bendingStiffness;
  double hi = 0.0;
  ElasticaTip tip;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (shoot(mid, tip) > 0.0) {
      hi = mid;
    } else {
      lo = mid;
    }
  }
  shoot(0.5 * (lo + hi), tip);
  return tip;
}

}  // namespace rope::test
