// SPDX-License-Identifier: MIT
#include "bullet_bridge/narrowphase/ray_capsule.h"

#include <cmath>

namespace rope::bullet {

namespace {

// Smallest root lambda in (0, 1] of |p(lambda) - c|^2 = r^2 for p = o + lambda d, entering the sphere.
bool raySphere(const btVector3& o, const btVector3& d, const btVector3& c, double r, double& lambda) {
  const btVector3 m = o - c;
  const double a = d.dot(d), b = m.dot(d), q = m.dot(m) - r * r;
  if (!(a > 0.0) || q <= 0.0) return false;  // degenerate ray, or starting inside
  const double disc = b * b - a * q;
  if (disc < 0.0) return false;
  const double root = (-b - std::sqrt(disc)) / a;
  if (root < 0.0 || root > 1.0) return false;
  lambda = root;
  return true;
}

}  // namespace

bool rayCapsule(const btVector3& o, const btVector3& d, const Capsule& capsule, double& lambda, double& t) {
  const btVector3 axis = capsule.b - capsule.a;
  const double axis2 = axis.dot(axis);
  const double r = capsule.radius;
  bool hit = false;
  double best = 2.0, bestT = 0.0;
  if (axis2 > 0.0) {
    // Infinite cylinder: components perpendicular to the axis.
    const btVector3 m = o - capsule.a;
    const btVector3 dp = d - axis * (d.dot(axis) / axis2);
    const btVector3 mp = m - axis * (m.dot(axis) / axis2);
    const double a = dp.dot(dp), b = mp.dot(dp), q = mp.dot(mp) - r * r;
    if (a > 0.0 && q > 0.0) {
      const double disc = b * b - a * q;
      if (disc >= 0.0) {
        const double root = (-b - std::sqrt(disc)) / a;
        if (root >= 0.0 && root <= 1.0) {
          const double along = (m + d * root).dot(axis) / axis2;
          if (along >= 0.0 && along <= 1.0) {
            hit = true;
            best = root;
            bestT = along;
          }
        }
      }
    }
  }
  double cap = 0.0;
  if (raySphere(o, d, capsule.a, r, cap) && cap < best) {
    hit = true;
    best = cap;
    bestT = 0.0;
  }
  if (raySphere(o, d, capsule.b, r, cap) && cap < best) {
    hit = true;
    best = cap;
    bestT = 1.0;
  }
  if (hit) {
    lambda = best;
    t = bestT;
  }
  return hit;
}

}  // namespace rope::bullet
