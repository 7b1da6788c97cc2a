// SPDX-License-Identifier: MIT
#include "rope/rod/bending_energy.h"

namespace rope {

double bendingEnergy(const RodIntegrals& integrals, const PointList& q) {
  double energy = 0.0;
  const int local = integrals.degree() + 1;
  for (int j = 0; j < integrals.spanCount(); ++j) {
    const SpanView span = integrals.span(j);
    // K_b annihilates translations (sum_b K_ab = 0), so measuring from a local origin gives the same
    // value without the cancellation of large absolute coordinates.
    const Vec3 origin = q[static_cast<size_t>(j)];
    for (int a = 0; a < local; ++a)
      for (int b = 0; b < local; ++b)
        energy += 0.5 * span.bending[a * local + b] *
                  (q[static_cast<size_t>(j + a)] - origin).dot(q[static_cast<size_t>(j + b)] - origin);
  }
  return energy;
}

void bendingForces(const RodIntegrals& integrals, const PointList& q, PointList& forces) {
  forces.assign(q.size(), Vec3::Zero());
  const int local = integrals.degree() + 1;
  for (int j = 0; j < integrals.spanCount(); ++j) {
    const SpanView span = integrals.span(j);
    const Vec3 origin = q[static_cast<size_t>(j)];
    for (int a = 0; a < local; ++a)
      for (int b = 0; b < local; ++b)
        forces[static_cast<size_t>(j + a)] -= span.bending[a * local + b] * (q[static_cast<size_t>(j + b)] - origin);
  }
}

void assembleBendingStiffness(const RodIntegrals& integrals, int controlPointCount,
                              SymmetricBandedMatrix& K) {
  const int local = integrals.degree() + 1;
  K.reset(controlPointCount, 1, integrals.degree());
  for (int j = 0; j < integrals.spanCount(); ++j) {
    const SpanView span = integrals.span(j);
    for (int a = 0; a < local; ++a)
      for (int b = 0; b <= a; ++b) K.at(j + a, j + b) += span.bending[a * local + b];
  }
}

}  // namespace rope
