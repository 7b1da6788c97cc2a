#include "rope/rod/bending_energy.h"

namespace rope {

double bendingEnergy(const RodIntegrals& integrals, const PointList& q) {
  double energy = 0.0;
  const int local = integrals.degree() + 1;
  for (int j = 0; j < integrals.spanCount(); ++j) {
    const SpanView span = integrals.span(j);
    for (int a = 0; a < local; ++a)
      for (int b = 0; b < local; ++b)
        energy += 0.5 * span.bending[a * local + b] *
                  q[static_cast<size_t>(j + a)].dot(q[static_cast<size_t>(j + b)]);
  }
  return energy;
}

void bendingForces(const RodIntegrals& integrals, const PointList& q, PointList& forces) {
  forces.assign(q.size(), Vec3::Zero());
  const int local = integrals.degree() + 1;
  for (int j = 0; j < integrals.spanCount(); ++j) {
    const SpanView span = integrals.span(j);
    for (int a = 0; a < local; ++a)
      for (int b = 0; b < local; ++b)
        forces[static_cast<size_t>(j + a)] -= span.bending[a * local + b] * q[static_cast<size_t>(j + b)];
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
