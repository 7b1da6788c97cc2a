// SPDX-License-Identifier: MIT
#include "rope/rod/stretching_energy.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "rope/spline/knot_insertion.h"
#include "rope/spline/knot_vector.h"
#include "tests/rope/rod/rod_test_util.h"

namespace rope {
namespace {

using test::straightRest;

// A random 3D configuration: the rest layout scaled by `stretch` along a random direction, bent and
// perturbed.
PointList randomConfiguration(const PointList& rest, double stretch, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> noise(-0.03, 0.03);
  PointList q;
  for (const Vec3& r : rest) {
    const double x = r.x() * stretch;
    q.emplace_back(x + noise(rng), 0.2 * std::sin(2.0 * x) + noise(rng), 0.1 * x * x + noise(rng));
  }
  return q;
}

Eigen::MatrixXd dense(const SymmetricBandedMatrix& m) {
  Eigen::MatrixXd out(m.size(), m.size());
  for (int r = 0; r < m.size(); ++r)
    for (int c = 0; c < m.size(); ++c) out(r, c) = m.entry(r, c);
  return out;
}

struct Case {
  int degree;
  double stretch;
  bool curvedRest;
  StretchingQuadrature quadrature = StretchingQuadrature::kExact;
};

class StretchingFiniteDifferences : public ::testing::TestWithParam<Case> {};

TEST_P(StretchingFiniteDifferences, ForceAndExactStiffnessMatchTheEnergy) {
  const Case c = GetParam();
  const KnotVector knots = KnotVector::clampedUniform(c.degree, 9, 0.0, 1.3);
  PointList rest = straightRest(knots);
  if (c.curvedRest) for (Vec3& p : rest) p.y() = 0.2 * std::cos(2.0 * p.x());
  RodIntegrals integrals;
  integrals.build(knots, rest, 0.1, 0.0, RodIntegrals::exactGaussCount(c.degree) + (c.curvedRest ? 4 : 0),
                  c.quadrature);
  const double ea = 3.0;
  for (unsigned seed = 1; seed <= 3; ++seed) {
    PointList q = randomConfiguration(rest, c.stretch, seed * 17u + static_cast<unsigned>(c.degree));
    PointList force;
    stretchingForces(integrals, q, ea, force);
    const int n = static_cast<int>(q.size());
    // Central differences of the energy: truncation O(eps^2), rounding O(1e-16 E / eps).
    const double eps = 1e-5;
    double largest = 0.0;
    for (const Vec3& f : force) largest = std::max(largest, f.cwiseAbs().maxCoeff());
    for (int i = 0; i < n; ++i) {
      for (int axis = 0; axis < 3; ++axis) {
        PointList plus = q, minus = q;
        plus[static_cast<size_t>(i)][axis] += eps;
        minus[static_cast<size_t>(i)][axis] -= eps;
        const double fd = -(stretchingEnergy(integrals, plus, ea) - stretchingEnergy(integrals, minus, ea)) / (2 * eps);
        EXPECT_NEAR(force[static_cast<size_t>(i)][axis], fd, 1e-6 * largest) << "i=" << i << " axis=" << axis;
      }
    }
    SymmetricBandedMatrix exact;
    assembleStretchingStiffness(integrals, q, ea, StiffnessMode::kExact, exact);
    const Eigen::MatrixXd K = dense(exact);
    const double kLargest = K.cwiseAbs().maxCoeff();
    for (int i = 0; i < n; ++i) {
      for (int axis = 0; axis < 3; ++axis) {
        PointList plus = q, minus = q;
        plus[static_cast<size_t>(i)][axis] += eps;
        minus[static_cast<size_t>(i)][axis] -= eps;
        PointList fPlus, fMinus;
        stretchingForces(integrals, plus, ea, fPlus);
        stretchingForces(integrals, minus, ea, fMinus);
        for (int m = 0; m < n; ++m)
          for (int b = 0; b < 3; ++b) {
            const double fd = -(fPlus[static_cast<size_t>(m)][b] - fMinus[static_cast<size_t>(m)][b]) / (2 * eps);
            EXPECT_NEAR(K(3 * m + b, 3 * i + axis), fd, 1e-6 * kLargest);
          }
      }
    }
    // The clamped stiffness the integrator uses is positive semidefinite.
    SymmetricBandedMatrix clamped;
    assembleStretchingStiffness(integrals, q, ea, StiffnessMode::kClamped, clamped);
    const Eigen::VectorXd eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense(clamped)).eigenvalues();
    EXPECT_GE(eigenvalues.minCoeff(), -1e-12 * kLargest);
    const double exactMin = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(K).eigenvalues().minCoeff();
    if (c.stretch < 1.0) {
      EXPECT_LT(exactMin, -1e-6 * kLargest) << "compressed: the exact Hessian is indefinite";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(StretchedAndCompressed, StretchingFiniteDifferences,
                         ::testing::Values(Case{3, 1.2, false}, Case{3, 0.7, false}, Case{2, 1.1, false},
                                           Case{2, 0.8, false}, Case{3, 1.15, true}, Case{3, 0.85, true},
                                           Case{4, 1.05, false},
                                           Case{3, 1.2, false, StretchingQuadrature::kLockingFree},
                                           Case{3, 0.8, true, StretchingQuadrature::kLockingFree},
                                           Case{2, 0.9, false, StretchingQuadrature::kLockingFree}));

// The Kelvin–Voigt damping's matrix (docs/method.md eq. 20): the exact stiffness without its tension
// term, block for block, so that v^T K_m v = sum_g EA W3 (C'.v')^2 is the strain-rate energy, and zero
// on a rigid rotation of a bent, stretched rope.
TEST(Stretching, MaterialStiffnessIsTheStiffnessWithoutItsTensionTermAndIgnoresRigidRotation) {
  const int degree = 3;
  const KnotVector knots = KnotVector::clampedUniform(degree, 9, 0.0, 1.3);
  RodIntegrals integrals;
  integrals.build(knots, straightRest(knots), 0.1, 0.0, RodIntegrals::exactGaussCount(degree),
                  StretchingQuadrature::kExact);
  const double ea = 3.0;
  const PointList q = randomConfiguration(straightRest(knots), 1.2, 5u);
  const int local = degree + 1;
  const Vec3 omega(0.3, -1.1, 0.7);  // rad/s
  double largest = 0.0, rotationResidual = 0.0;
  for (int j = 0; j < integrals.spanCount(); ++j) {
    const SpanView span = integrals.span(j);
    const Vec3* x = &q[static_cast<size_t>(j)];
    Vec3 force[kMaxDegree + 1];
    for (Vec3& f : force) f.setZero();
    Eigen::Matrix3d exact[(kMaxDegree + 1) * (kMaxDegree + 1)], material[(kMaxDegree + 1) * (kMaxDegree + 1)];
    stretchingSpan(span, x, ea, StiffnessMode::kExact, force, exact);
    materialStiffnessSpan(span, x, ea, material);
    // The tension term (EA/2) t b'_a b'_b I, t = W3 |C'|^2 - W1, rebuilt from the integrals.
    double tensionWeight[(kMaxDegree + 1) * (kMaxDegree + 1)] = {};
    for (int g = 0; g < span.gaussCount; ++g) {
      const double* db = span.dBasis + g * local;
      Vec3 tangent = Vec3::Zero();
      for (int a = 0; a < local; ++a) tangent += db[a] * x[a];
      const double t = span.w3[g] * tangent.squaredNorm() - span.w1[g];
      for (int a = 0; a < local; ++a)
        for (int b = 0; b <= a; ++b) tensionWeight[a * local + b] += 0.5 * ea * t * db[a] * db[b];
    }
    for (int a = 0; a < local; ++a) {
      Vec3 rotation = Vec3::Zero();  // (K_m v)_a for v_b = omega x q_b
      for (int b = 0; b < local; ++b) {
        const Eigen::Matrix3d& m = a >= b ? material[a * local + b] : material[b * local + a];
        rotation += m * omega.cross(x[b]);
        largest = std::max(largest, m.cwiseAbs().maxCoeff() * omega.norm() * x[b].norm());
        if (b > a) continue;
        const Eigen::Matrix3d expected =
            exact[a * local + b] - tensionWeight[a * local + b] * Eigen::Matrix3d::Identity();
        EXPECT_LT((material[a * local + b] - expected).cwiseAbs().maxCoeff(),
                  1e-13 * exact[a * local + b].cwiseAbs().maxCoeff() + 1e-15)
            << "span " << j << " block " << a << "," << b;
      }
      rotationResidual = std::max(rotationResidual, rotation.cwiseAbs().maxCoeff());
    }
  }
  EXPECT_LT(rotationResidual, 1e-13 * largest);
}

TEST(Stretching, LockingFreeRuleSamplesTheStrainSpaceOnce) {
  // n - 1 strain samples in all (the dimension of the degree d-1 spline space of C').
  for (int degree : {2, 3, 4}) {
    const KnotVector knots = KnotVector::clampedUniform(degree, 11, 0.0, 1.0);
    RodIntegrals integrals;
    integrals.build(knots, straightRest(knots), 0.1, 0.0, RodIntegrals::exactGaussCount(degree),
                    StretchingQuadrature::kLockingFree);
    int samples = 0;
    double restLength = 0.0;
    for (int j = 0; j < integrals.spanCount(); ++j) {
      samples += integrals.span(j).gaussCount;
      for (int g = 0; g < integrals.span(j).gaussCount; ++g) restLength += integrals.span(j).w0[g];
    }
    EXPECT_EQ(samples, 10) << "degree " << degree;
    EXPECT_NEAR(restLength, 1.0, 1e-14);  // each rule integrates constants exactly
  }
}

TEST(Stretching, LockingFreeRulePassesThePatchTestOnNonUniformKnots) {
  // Its weights integrate every b_i' exactly, so a uniform strain is an exact equilibrium: the
  // internal force vanishes on all interior control points.
  KnotVector knots(3, {0.0, 0.0, 0.0, 0.0, 0.05, 0.3, 0.35, 0.6, 0.62, 0.9, 1.0, 1.0, 1.0, 1.0});
  PointList rest = straightRest(knots);
  RodIntegrals integrals;
  integrals.build(knots, rest, 0.1, 0.0, RodIntegrals::exactGaussCount(3), StretchingQuadrature::kLockingFree);
  PointList stretched = rest;
  for (Vec3& p : stretched) p *= 1.01;
  PointList force;
  stretchingForces(integrals, stretched, 100.0, force);
  const double tension = 0.5 * 100.0 * 1.01 * (1.01 * 1.01 - 1.0);  // (EA/2) gamma (gamma^2 - 1)
  for (size_t i = 1; i + 1 < force.size(); ++i) EXPECT_LT(force[i].norm(), 1e-12 * tension) << i;
  EXPECT_NEAR(force.front().x(), tension, 1e-12 * tension);
  EXPECT_NEAR(force.back().x(), -tension, 1e-12 * tension);
  // Refinement keeps the property (the weights are rebalanced after each change).
  const KnotInsertion plan = insertKnot(knots, stretched, 0.41);
  plan.apply(rest);
  integrals.afterInsertion(plan, knots, rest);
  stretchingForces(integrals, stretched, 100.0, force);
  for (size_t i = 1; i + 1 < force.size(); ++i) EXPECT_LT(force[i].norm(), 1e-12 * tension) << i;
}

TEST(Stretching, RestStateHasNoEnergyNoForceAndUniformStrainIsExact) {
  const KnotVector knots = KnotVector::clampedUniform(3, 10, 0.0, 2.0);
  const PointList rest = straightRest(knots);
  RodIntegrals integrals;
  integrals.build(knots, rest, 0.1, 0.0, RodIntegrals::exactGaussCount(3));
  EXPECT_NEAR(stretchingEnergy(integrals, rest, 5.0), 0.0, 1e-28);
  PointList force;
  stretchingForces(integrals, rest, 5.0, force);
  for (const Vec3& f : force) EXPECT_LT(f.norm(), 1e-13);
  // Uniform stretch gamma: E = (EA/8)(gamma^2 - 1)^2 L (docs/method.md eq. 13).
  PointList stretched = rest;
  const double gamma = 1.1;
  for (Vec3& p : stretched) p *= gamma;
  const double expected = 5.0 / 8.0 * (gamma * gamma - 1.0) * (gamma * gamma - 1.0) * 2.0;
  EXPECT_NEAR(stretchingEnergy(integrals, stretched, 5.0), expected, 1e-13);
  EXPECT_NEAR(maxStrain(integrals, stretched), 0.1, 1e-13);
  // Clamp only acts under compression: stretched, clamped == exact.
  SymmetricBandedMatrix a, b;
  assembleStretchingStiffness(integrals, stretched, 5.0, StiffnessMode::kExact, a);
  assembleStretchingStiffness(integrals, stretched, 5.0, StiffnessMode::kClamped, b);
  for (int r = 0; r < a.size(); ++r)
    for (int c = 0; c < a.size(); ++c) EXPECT_EQ(a.entry(r, c), b.entry(r, c));
}

}  // namespace
}  // namespace rope
