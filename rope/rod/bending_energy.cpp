// SPDX-License-Identifier: MIT
#include "rope/rod/bending_energy.h"

namespace rope {

double bendingSpan(const SpanView& span, const Vec3* q, Vec3* force, double sum) {
  const int local = span.localCount;
  // K_b annihilates translations (sum_b K_ab = 0), so measuring from a local origin gives the same
  // value without the cancellation of large absolute coordinates.
  Vec3 x[kMaxDegree + 1];
  for (int a = 0; a < local; ++a) x[a] = q[a] - q[0];
  double energy = sum;
  for (int a = 0; a < local; ++a)
    for (int b = 0; b < local; ++b) energy += 0.5 * span.bending[a * local + b] * x[a].dot(x[b]);
  if (force != nullptr) {
    for (int a = 0; a < local; ++a)
      for (int b = 0; b < local; ++b) force[a] -= span.bending[a * local + b] * x[b];
  }
  return energy;
}

double bendingEnergy(const RodIntegrals& integrals, const PointList& q) {
  double energy = 0.0;
  for (int j = 0; j < integrals.spanCount(); ++j)
    energy = bendingSpan(integrals.span(j), &q[static_cast<size_t>(j)], nullptr, energy);
  return energy;
}

void bendingForces(const RodIntegrals& integrals, const PointList& q, PointList& forces) {
  forces.assign(q.size(), Vec3::Zero());
  for (int j = 0; j < integrals.spanCount(); ++j)
    bendingSpan(integrals.span(j), &q[static_cast<size_t>(j)], &forces[static_cast<size_t>(j)]);
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
