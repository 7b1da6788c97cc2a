#include "bullet_bridge/capsule.h"

#include "rope/common/error.h"

namespace rope::bullet {

namespace {

void requireFinitePoint(const std::string& name, const btVector3& p) {
  static const char* const kAxes[3] = {".x", ".y", ".z"};
  for (int i = 0; i < 3; ++i) requireFinite(name + kAxes[i], p[i]);
}

}  // namespace

void requireValidCapsule(const std::string& name, const Capsule& capsule) {
  requireFinitePoint(name + ".a", capsule.a);
  requireFinitePoint(name + ".b", capsule.b);
  requirePositive(name + ".radius", capsule.radius);
}

}  // namespace rope::bullet
