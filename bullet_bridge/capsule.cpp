// SPDX-License-Identifier: MIT
#include "bullet_bridge/capsule.h"

#include <cmath>

#include "rope/common/error.h"

namespace rope::bullet {

namespace {

void requireFinitePoint(const std::string& name, const btVector3& p) {
  static const char* const kAxes[3] = {".x", ".y", ".z"};
  for (int i = 0; i < 3; ++i) requireFinite(name + kAxes[i], p[i]);
}

}  // namespace

void requireValidCapsule(const std::string& name, const Capsule& capsule) {
  // Fast path without building parameter names: this runs once per narrowphase query.
  bool finite = std::isfinite(capsule.radius);
  for (int i = 0; i < 3; ++i) {
    finite = finite && std::isfinite(capsule.a[i]) && std::isfinite(capsule.b[i]);
  }
  if (finite && capsule.radius > 0) return;
  requireFinitePoint(name + ".a", capsule.a);
  requireFinitePoint(name + ".b", capsule.b);
  requirePositive(name + ".radius", capsule.radius);
}

}  // namespace rope::bullet
