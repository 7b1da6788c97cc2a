// SPDX-License-Identifier: MIT
#include "rope/rod/stretching_energy.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rope {

double stretchingSpan(const SpanView& span, const Vec3* q, double axialStiffness, StiffnessMode mode,
                      Vec3* force, Eigen::Matrix3d* stiffness) {
  const int local = span.localCount;
  const double halfEA = 0.5 * axialStiffness;
  double energy = 0.0;
  if (stiffness != nullptr) {
    for (int a = 0; a < local; ++a)
      for (int b = 0; b <= a; ++b) stiffness[a * local + b].setZero();
  }
  for (int g = 0; g < span.gaussCount; ++g) {
    const double w1 = span.w1[g];
    if (w1 == 0.0) continue;  // empty span
    const double w3 = span.w3[g];
    const double* db = span.dBasis + g * local;
    Vec3 tangent = Vec3::Zero();  // C'(s_g)
    for (int a = 0; a < local; ++a) tangent += db[a] * q[a];
    const double c2 = tangent.squaredNorm();
    const double strain2 = c2 * (w3 / w1) - 1.0;  // gamma^2 - 1, without cancellation in W3 c2^2 - 2 W1 c2 + W0
    energy += 0.125 * axialStiffness * span.w0[g] * strain2 * strain2;
    const double t = w1 * strain2;
    if (force != nullptr) {
      for (int a = 0; a < local; ++a) force[a] -= (halfEA * t * db[a]) * tangent;
    }
    if (stiffness != nullptr) {
      const double isotropic = halfEA * (mode == StiffnessMode::kExact ? t : std::max(t, 0.0));
      Eigen::Matrix3d h = (axialStiffness * w3) * (tangent * tangent.transpose());
      h.diagonal().array() += isotropic;
      for (int a = 0; a < local; ++a)
        for (int b = 0; b <= a; ++b) stiffness[a * local + b] += (db[a] * db[b]) * h;
    }
  }
  return energy;
}

void materialStiffnessSpan(const SpanView& span, const Vec3* q, double axialStiffness, Eigen::Matrix3d* stiffness) {
  const int local = span.localCount;
  for (int a = 0; a < local; ++a)
    for (int b = 0; b <= a; ++b) stiffness[a * local + b].setZero();
  for (int g = 0; g < span.gaussCount; ++g) {
    if (span.w1[g] == 0.0) continue;  // empty span
    const double* db = span.dBasis + g * local;
    Vec3 tangent = Vec3::Zero();  // C'(s_g)
    for (int a = 0; a < local; ++a) tangent += db[a] * q[a];
    const Eigen::Matrix3d h = (axialStiffness * span.w3[g]) * (tangent * tangent.transpose());
    for (int a = 0; a < local; ++a)
      for (int b = 0; b <= a; ++b) stiffness[a * local + b] += (db[a] * db[b]) * h;
  }
}

double stretchingEnergy(const RodIntegrals& integrals, const PointList& q, double axialStiffness) {
  double energy = 0.0;
  for (int j = 0; j < integrals.spanCount(); ++j) {
    energy += stretchingSpan(integrals.span(j), &q[static_cast<size_t>(j)], axialStiffness,
                             StiffnessMode::kExact, nullptr, nullptr);
  }
  return energy;
}

void stretchingForces(const RodIntegrals& integrals, const PointList& q, double axialStiffness,
                      PointList& forces) {
  forces.assign(q.size(), Vec3::Zero());
  for (int j = 0; j < integrals.spanCount(); ++j) {
    stretchingSpan(integrals.span(j), &q[static_cast<size_t>(j)], axialStiffness,
                   StiffnessMode::kExact, &forces[static_cast<size_t>(j)], nullptr);
  }
}

void assembleStretchingStiffness(const RodIntegrals& integrals, const PointList& q,
                                 double axialStiffness, StiffnessMode mode, SymmetricBandedMatrix& K) {
  const int d = integrals.degree();
  const int local = d + 1;
  K.reset(static_cast<int>(q.size()), 3, d);
  Vec3 scratch[kMaxDegree + 1];
  Eigen::Matrix3d blocks[(kMaxDegree + 1) * (kMaxDegree + 1)];
  for (int j = 0; j < integrals.spanCount(); ++j) {
    stretchingSpan(integrals.span(j), &q[static_cast<size_t>(j)], axialStiffness, mode, scratch, blocks);
    for (int a = 0; a < local; ++a)
      for (int b = 0; b <= a; ++b) K.addBlock(j + a, j + b, blocks[a * local + b]);
  }
}

double maxStrain(const RodIntegrals& integrals, const PointList& q) {
  double largest = -std::numeric_limits<double>::infinity();
  for (int j = 0; j < integrals.spanCount(); ++j) {
    const SpanView span = integrals.span(j);
    for (int g = 0; g < span.gaussCount; ++g) {
      if (span.w1[g] == 0.0) continue;
      const double* db = span.dBasis + g * span.localCount;
      Vec3 tangent = Vec3::Zero();
      for (int a = 0; a < span.localCount; ++a) tangent += db[a] * q[static_cast<size_t>(j + a)];
      const double gamma = std::sqrt(tangent.squaredNorm() * (span.w3[g] / span.w1[g]));
      largest = std::max(largest, gamma - 1.0);
    }
  }
  return largest;
}

}  // namespace rope
