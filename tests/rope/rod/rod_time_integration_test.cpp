// SPDX-License-Identifier: MIT
// Scenario: the time integrators of docs/method.md §8 on a rope pendulum with a heavy end mass (a 10 kg
// point mass on 1 m of thin rope, swung by 5 degrees), and an undamped free rope's energy. BDF2, the
// default (method eqs. 22a–22c), must keep the swing; backward Euler (eq. 22) is measured beside it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "rope/common/error.h"
#include "rope/rod/rod.h"

namespace rope {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kBob = 10.0;    // kg
constexpr double kRopeMu = 0.01; // kg/m
constexpr double kG = 9.81;
constexpr double kSwing = 5.0 * kPi / 180.0;

RodSettings pendulumSettings(TimeIntegrator integrator) {
  RodSettings settings;
  settings.restLength = 1.0;
  settings.radius = 0.002;
  settings.linearDensity = kRopeMu;
  settings.timeIntegrator = integrator;
  return settings;  // the default damping (material, 1 ms) and adaptivity
}

// Stretch gamma of the rope under the bob's weight, from the Green–Lagrange law (method eq. 13):
// T = (EA/2) gamma (gamma^2 - 1). Solved by Newton's method.
double hangingStretch(double tension, double ea) {
  double gamma = 1.0 + tension / ea;
  for (int i = 0; i < 50; ++i) {
    const double f = 0.5 * ea * gamma * (gamma * gamma - 1.0) - tension;
    gamma -= f / (0.5 * ea * (3.0 * gamma * gamma - 1.0));
  }
  return gamma;
}

// Small-swing period of the bob on the stretched rope treated as a rigid uniform bar (its own mass
// mu L counted as such: I = (M + m/3) L^2 about the pin, gravity torque (M + m/2) g L per radian), with
// the finite-amplitude series 1 + theta0^2/16 + 11 theta0^4/3072.
double analyticPeriod(double length) {
  const double rope = kRopeMu * 1.0;
  const double small = 2.0 * kPi * std::sqrt((kBob + rope / 3.0) * length / ((kBob + rope / 2.0) * kG));
  return small * (1.0 + kSwing * kSwing / 16.0 + 11.0 * std::pow(kSwing, 4) / 3072.0);
}

struct Swing {
  double amplitudeKept = 0.0;  // largest |angle| over the last period / over the first
  double period = 0.0;         // s, mean over the run
  double expectedPeriod = 0.0; // s
};

Swing swing(TimeIntegrator integrator, double h, double seconds) {
  const RodSettings settings = pendulumSettings(integrator);
  const double gamma = hangingStretch(kBob * kG, settings.axialStiffness());
  const double length = gamma * settings.restLength;
  Rod rod = Rod::fromSegment(settings, Vec3(0, 0, 0), length * Vec3(std::sin(kSwing), -std::cos(kSwing), 0));
  rod.pin(0.0);
  rod.addPointMass(rod.endParameter(), kBob);
  const int steps = static_cast<int>(std::lround(seconds / h));
  std::vector<double> crossings;
  std::vector<std::pair<double, double>> angles;  // (t, angle)
  double previous = std::atan2(rod.position(rod.endParameter()).x(), -rod.position(rod.endParameter()).y());
  angles.emplace_back(0.0, previous);
  for (int i = 1; i <= steps; ++i) {
    const StepReport report = rod.step(h);
    EXPECT_TRUE(report.ok) << report.failure;
    if (!report.ok) break;
    const Vec3 end = rod.position(rod.endParameter());
    const double angle = std::atan2(end.x(), -end.y());
    if (previous < 0.0 && angle >= 0.0) crossings.push_back((i - 1 + previous / (previous - angle)) * h);
    angles.emplace_back(i * h, angle);
    previous = angle;
  }
  Swing result;
  result.expectedPeriod = analyticPeriod(length);
  if (crossings.size() >= 2) result.period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  double first = 0.0, last = 0.0;
  for (const auto& [t, angle] : angles) {
    if (t <= result.expectedPeriod) first = std::max(first, std::abs(angle));
    if (t >= seconds - result.expectedPeriod) last = std::max(last, std::abs(angle));
  }
  result.amplitudeKept = last / first;
  return result;
}

class PendulumSwing : public ::testing::TestWithParam<double> {};

TEST_P(PendulumSwing, Bdf2KeepsTheSwingAndThePeriod) {
  const double h = GetParam();
  const Swing bdf2 = swing(TimeIntegrator::kBdf2, h, 20.0);
  const Swing euler = swing(TimeIntegrator::kBackwardEuler, h, 20.0);
  const double periodError = bdf2.period / bdf2.expectedPeriod - 1.0;
  std::printf("[pendulum h=1/%.0f] BDF2 keeps %.4f%% of the swing over 20 s, period %.6f s vs %.6f s (%.2e); "
              "backward Euler keeps %.4f%% (period error %.2e)\n",
              1.0 / h, 100.0 * bdf2.amplitudeKept, bdf2.period, bdf2.expectedPeriod, periodError,
              100.0 * euler.amplitudeKept, euler.period / euler.expectedPeriod - 1.0);
  EXPECT_GE(bdf2.amplitudeKept, h < 1.0 / 100 ? 0.98 : 0.95);
  EXPECT_LE(bdf2.amplitudeKept, 1.0 + 1e-3);  // and it does not grow
  EXPECT_LT(std::abs(periodError), 1e-3);
  // The first-order step loses far more (the 30 % at 1/240 s): the test tells them apart.
  EXPECT_LT(euler.amplitudeKept, 0.9);
}

INSTANTIATE_TEST_SUITE_P(TimeSteps, PendulumSwing, ::testing::Values(1.0 / 240, 1.0 / 60));

// A free rope (no gravity, no pins, no damping) flung with a random smooth velocity field tumbles and
// flexes; BDF2's energy must not grow over the run.
TEST(TimeIntegration, UndampedFreeRopeEnergyDoesNotGrow) {
  for (const double h : {1.0 / 240, 1.0 / 60}) {
    RodSettings settings;
    settings.gravity = Vec3::Zero();
    settings.materialDamping = 0.0;
    settings.timeIntegrator = TimeIntegrator::kBdf2;
    Rod rod = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(1, 0, 0));
    std::mt19937 random(7);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    PointList velocities;
    for (int i = 0; i < rod.controlPointCount(); ++i) velocities.emplace_back(uniform(random), uniform(random), uniform(random));
    rod.setVelocities(velocities);
    const double initial = rod.totalEnergy();
    double largest = initial;
    const int steps = static_cast<int>(std::lround(20.0 / h));
    for (int i = 0; i < steps; ++i) {
      ASSERT_TRUE(rod.step(h).ok) << i;
      largest = std::max(largest, rod.totalEnergy());
    }
    std::printf("[free rope h=1/%.0f] energy %.6e J -> %.6e J after 20 s, largest %.6e J (%.2e above the start)\n",
                1.0 / h, initial, rod.totalEnergy(), largest, largest / initial - 1.0);
    EXPECT_LE(rod.totalEnergy(), initial);
    EXPECT_LE(largest, initial * (1.0 + 1e-9));
  }
}

TEST(TimeIntegration, PointMassCountsInMassMomentumAndEnergyAndRejectsBadInput) {
  Rod rod = Rod::fromSegment(RodSettings(), Vec3(0, 0, 0), Vec3(1, 0, 0));
  const double ropeMass = rod.mass();
  rod.addPointMass(0.5, 2.0);
  EXPECT_NEAR(rod.mass(), ropeMass + 2.0, 1e-15);
  rod.setVelocities(PointList(static_cast<size_t>(rod.controlPointCount()), Vec3(0, 3, 0)));
  EXPECT_NEAR(rod.momentum().y(), 3.0 * (ropeMass + 2.0), 1e-12);
  EXPECT_NEAR(rod.kineticEnergy(), 4.5 * (ropeMass + 2.0), 1e-12);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const double bad : {0.0, -1.0, nan, std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(rod.addPointMass(0.5, bad), InvalidArgument);
  }
  for (const double bad : {-0.1, 1.5, nan}) EXPECT_THROW(rod.addPointMass(bad, 1.0), InvalidArgument);
  EXPECT_EQ(rod.pointMasses().size(), 1u);  // the refused calls changed nothing
  // Gravity pulls it: one step from rest moves the rope's momentum by (m_rope + m) g h.
  rod.setVelocities(PointList(static_cast<size_t>(rod.controlPointCount()), Vec3::Zero()));
  ASSERT_TRUE(rod.step(1.0 / 240).ok);
  EXPECT_NEAR(rod.momentum().y(), -9.81 * (ropeMass + 2.0) / 240, 1e-12);
}

}  // namespace
}  // namespace rope
