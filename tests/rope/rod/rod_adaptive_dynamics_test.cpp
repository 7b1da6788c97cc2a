// SPDX-License-Identifier: MIT
// Adaptivity that keeps the dynamics (docs/method.md §10), all with adaptivity on:
//   - knot removal keeps a free rope's linear momentum (with either removal criterion);
//   - the first three transverse modes of a taut string and of a rope hanging from one end keep their
//     analytic frequencies with the default removal criterion (kMechanicalOutOfContact, which is
//     kMechanical for a rope out of contact), while the same ropes straight and still are coarsened
//     below the uniform count they started with.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <vector>

#include "rope/common/error.h"
#include "rope/rod/rod.h"
#include "tests/rope/rod/rod_test_util.h"

namespace rope {
namespace {

constexpr double kPi = 3.14159265358979323846;

using test::angularMomentum;  // L = sum_ij M_ij q_i x v_j, about the origin

struct Drift {
  double linear = 0.0;   // max |P - P0| / |P0| over the run
  double angular = 0.0;  // max |L - L0| / |L0|
  int insertions = 0;
  int removals = 0;
  double removalAngular = 0.0;    // sum of |dL| over the explicit removals, kg m^2/s
  double removalAllowance = 0.0;  // sum of their bounds from the reported removal errors
};

// A free rope (no gravity) flung with a random velocity field: steps with adaptivity, explicit knot
// insertions, then explicit and adaptive removals. Momentum is checked after every change.
Drift flingAndCoarsen(const RodSettings& settings, unsigned seed) {
  Rod rod = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(1, 0, 0));
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  PointList velocities;
  for (int i = 0; i < rod.controlPointCount(); ++i)
    velocities.emplace_back(1.0 + 0.5 * unit(random), 0.5 * unit(random), 0.5 * unit(random));
  rod.setVelocities(velocities);
  const Vec3 p0 = rod.momentum();
  const Vec3 l0 = angularMomentum(rod);
  Drift drift;
  auto check = [&]() {
    drift.linear = std::max(drift.linear, (rod.momentum() - p0).norm() / p0.norm());
    drift.angular = std::max(drift.angular, (angularMomentum(rod) - l0).norm() / l0.norm());
  };
  auto run = [&](int steps) {
    for (int i = 0; i < steps; ++i) {
      const StepReport report = rod.step(1.0 / 240);
      EXPECT_TRUE(report.ok) << report.failure;
      drift.insertions += report.insertions;
      drift.removals += report.removals;
      check();
    }
  };
  run(24);
  // Explicit insertions at random places (exact: the fields do not change) ...
  for (int k = 0; k < 6; ++k) {
    const double s = 0.05 + 0.9 * (0.5 + 0.5 * unit(random));
    try {
      rod.insertKnot(s);
      ++drift.insertions;
    } catch (const InvalidArgument&) {
      // too close to an existing knot: skip
    }
    check();
  }
  run(24);
  // ... and explicit removals of interior knots, which the curved, moving rope does not allow by
  // the adaptive bounds: each changes the fields by its removal error, momentum must stay.
  for (int k = 0; k < 7 && rod.controlPointCount() > rod.degree() + 2; ++k) {
    const std::vector<double>& knots = rod.knots().values();
    const size_t middle = knots.size() / 2;
    // What a removal may do to L = int mu C x V: |dL| <= m (max|dC| max|V| + max|C| max|dV|),
    // with the fields' changes as removeKnot reports them and the maxima over the control points.
    double reach = 0.0, speed = 0.0;
    for (const Vec3& q : rod.controlPoints()) reach = std::max(reach, q.norm());
    for (const Vec3& v : rod.velocities()) speed = std::max(speed, v.norm());
    const Vec3 before = angularMomentum(rod);
    const RemovalReport report = rod.removeKnot(knots[middle]);
    for (const Vec3& v : rod.velocities()) speed = std::max(speed, v.norm());
    drift.removalAngular += (angularMomentum(rod) - before).norm();
    drift.removalAllowance +=
        rod.mass() * (report.positionError * speed + (reach + report.positionError) * report.velocityError);
    ++drift.removals;
    check();
  }
  run(48);
  return drift;
}

TEST(AdaptiveDynamics, KnotRemovalKeepsTheLinearMomentumOfAFlungRope) {
  RodSettings settings;  // default: adaptive
  settings.gravity = Vec3::Zero();  // the default removal criterion: kMechanical out of contact
  const Drift mechanical = flingAndCoarsen(settings, 7u);
  // The polygon criterion removes far more knots adaptively from the same motion; the projection
  // must keep momentum through those too.
  settings.removalCriterion = RemovalCriterion::kPolygon;
  settings.removalErrorBound = 1e-2;
  settings.removalVelocityErrorBound = 1e-1;
  const Drift polygon = flingAndCoarsen(settings, 7u);
  std::printf("[fling] kMechanical: %d insertions, %d removals, momentum drift %.2e; angular momentum drift %.2e "
              "(steps included), by the explicit removals %.2e kg m^2/s against their bound %.2e\n",
              mechanical.insertions, mechanical.removals, mechanical.linear, mechanical.angular,
              mechanical.removalAngular, mechanical.removalAllowance);
  std::printf("[fling] kPolygon (loose bounds): %d insertions, %d removals, momentum drift %.2e; angular momentum "
              "drift %.2e, by the explicit removals %.2e against %.2e\n",
              polygon.insertions, polygon.removals, polygon.linear, polygon.angular, polygon.removalAngular,
              polygon.removalAllowance);
  EXPECT_GE(mechanical.removals, 7);
  EXPECT_GT(polygon.removals, mechanical.removals);
  EXPECT_LT(mechanical.linear, 1e-10);
  EXPECT_LT(polygon.linear, 1e-10);
  // Angular momentum is not conserved by the projection (nor by the step: see rod_energy_test.cpp);
  // a removal changes it by at most what its position and velocity errors allow.
  EXPECT_GT(mechanical.removalAngular, 0.0);
  EXPECT_LE(mechanical.removalAngular, mechanical.removalAllowance);
  EXPECT_LE(polygon.removalAngular, polygon.removalAllowance);
}

TEST(AdaptiveDynamics, RemoveKnotKeepsMomentumAndReportsTheVelocityChange) {
  RodSettings settings;
  settings.gravity = Vec3::Zero();
  settings.adaptive = false;
  Rod rod = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(1, 0, 0));
  // A velocity field that is a cubic on the coarse knots: the removal is exact, nothing to correct.
  PointList uniform(static_cast<size_t>(rod.controlPointCount()), Vec3(0.3, -0.2, 0.1));
  rod.setVelocities(uniform);
  const RemovalReport exact = rod.removeKnot(rod.knots().values()[8]);
  EXPECT_LT(exact.velocityError, 1e-14);
  for (const Vec3& v : rod.velocities()) EXPECT_LT((v - Vec3(0.3, -0.2, 0.1)).norm(), 1e-14);
  // A field the coarse spline cannot hold: the removal changes it, restores the momentum, and says by
  // how much the field moved (rod_test.cpp checks that bound on samples).
  PointList wavy;
  for (int i = 0; i < rod.controlPointCount(); ++i) wavy.emplace_back(0, (i % 2 == 0 ? 0.1 : -0.1), 0);
  rod.setVelocities(wavy);
  const Vec3 before = rod.momentum();
  const RemovalReport inexact = rod.removeKnot(rod.knots().values()[8]);
  EXPECT_GT(inexact.velocityError, 1e-3);
  EXPECT_LT(inexact.velocityError, 1.0);  // measured 0.33 (the sweep's error on a zigzag)
  EXPECT_LT((rod.momentum() - before).norm(), 1e-15 + 1e-12 * rod.mass() * 0.1);
}

// ---- vibration ----

// Upward zero crossings of a sampled signal -> frequency (Hz), linear interpolation in time.
struct CrossingCounter {
  double previous = 0.0;
  bool started = false;
  std::vector<double> crossings;
  void add(double t, double h, double value) {
    if (started && previous < 0.0 && value >= 0.0) crossings.push_back(t - h + h * previous / (previous - value));
    previous = value;
    started = true;
  }
  double frequency() const {
    if (crossings.size() < 3) return 0.0;
    return static_cast<double>(crossings.size() - 1) / (crossings.back() - crossings.front());
  }
};

struct ModeRun {
  double frequency = 0.0;  // Hz
  int minPoints = 1 << 30;
  int maxPoints = 0;
};

// Steps `rod` for `seconds` and measures the frequency of the modal coordinate
// a(t) = sum_m (C(s_m) - C_0(s_m)) . e shape(s_m) over 64 samples (the mode's projection, which filters
// the other modes out), e the displacement direction.
ModeRun measureMode(Rod& rod, const std::function<double(double)>& shape, const Vec3& direction, double h,
                    double seconds) {
  const int samples = 64;
  std::vector<double> s(samples);
  std::vector<Vec3> rest(samples);
  for (int m = 0; m < samples; ++m) {
    s[static_cast<size_t>(m)] = rod.beginParameter() + (m + 0.5) / samples * (rod.endParameter() - rod.beginParameter());
    rest[static_cast<size_t>(m)] = rod.position(s[static_cast<size_t>(m)]);
  }
  ModeRun run;
  CrossingCounter counter;
  const int steps = static_cast<int>(std::lround(seconds / h));
  for (int i = 1; i <= steps; ++i) {
    const StepReport report = rod.step(h);
    EXPECT_TRUE(report.ok) << report.failure;
    run.minPoints = std::min(run.minPoints, report.controlPoints);
    run.maxPoints = std::max(run.maxPoints, report.controlPoints);
    double a = 0.0;
    for (int m = 0; m < samples; ++m)
      a += (rod.position(s[static_cast<size_t>(m)]) - rest[static_cast<size_t>(m)]).dot(direction) *
           shape(s[static_cast<size_t>(m)]);
    counter.add(i * h, h, a);
  }
  run.frequency = counter.frequency();
  return run;
}

// Sets the velocity field amplitude * shape(s) * direction by interpolating at the Greville abscissae.
void setModeVelocity(Rod& rod, const std::function<double(double)>& shape, const Vec3& direction, double amplitude) {
  const std::vector<double>& knots = rod.knots().values();
  const int d = rod.degree();
  PointList velocities = rod.velocities();
  for (int i = 0; i < rod.controlPointCount(); ++i) {
    double greville = 0.0;
    for (int k = 1; k <= d; ++k) greville += knots[static_cast<size_t>(i + k)];
    velocities[static_cast<size_t>(i)] += amplitude * shape(greville / d) * direction;
  }
  rod.setVelocities(velocities);
}

// Taut string as in rod_taut_string_test.cpp: 0.99 m of rope (EA = 1 kN, 0.1 kg/m, no bending) pinned
// 1 m apart, no gravity: f_k = k c / (2 D) with the Green–Lagrange tension.
constexpr double kSpan = 1.0;
constexpr double kStringRest = 0.99;

RodSettings stringSettings() {
  RodSettings settings;
  settings.restLength = kStringRest;
  settings.linearDensity = 0.1;
  settings.youngsModulus = 1000.0 / settings.area();
  settings.bendingStiffness = 0.0;
  settings.gravity = Vec3::Zero();
  return settings;  // default adaptivity otherwise: on, 16 initial control points
}

TEST(AdaptiveDynamics, TautStringKeepsItsFirstThreeModesAndCoarsensWhenStill) {
  const RodSettings settings = stringSettings();
  const double eps = kSpan / kStringRest - 1.0;
  const double tension = settings.axialStiffness() * eps * (1.0 + eps) * (1.0 + 0.5 * eps);
  const double c = std::sqrt(tension * kSpan / (settings.linearDensity * kStringRest));
  const double h = 1.0 / 4000;
  for (int k = 1; k <= 3; ++k) {
    const double exact = k * c / (2.0 * kSpan);
    Rod rod = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(kSpan, 0, 0));
    rod.pin(rod.beginParameter());
    rod.pin(rod.endParameter());
    auto shape = [k](double s) { return std::sin(k * kPi * s / kStringRest); };
    // 0.1 mm amplitude: the tension it adds is 1e-5 of the prestress.
    setModeVelocity(rod, shape, Vec3::UnitY(), 1e-4 * 2.0 * kPi * exact);
    const ModeRun run = measureMode(rod, shape, Vec3::UnitY(), h, 4.0 / k * 0.5);
    const double error = run.frequency / exact - 1.0;
    std::printf("[adaptive taut string] mode %d: f %.5f Hz (exact %.5f), error %+.2e, control points %d..%d\n", k,
                run.frequency, exact, error, run.minPoints, run.maxPoints);
    // Issue target 1 %; measured with the default criterion within 2.0e-3 (fixed 16: 0.07 %).
    EXPECT_LT(std::abs(error), 5e-3) << "mode " << k;
  }
  // The same string straight and still: coarsened below the 16 points it started with.
  Rod still = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(kSpan, 0, 0));
  still.pin(still.beginParameter());
  still.pin(still.endParameter());
  for (int i = 0; i < 100; ++i) ASSERT_TRUE(still.step(h).ok);
  std::printf("[adaptive taut string] still: %d control points (uniform %d)\n", still.controlPointCount(),
              settings.initialControlPoints);
  EXPECT_LT(still.controlPointCount(), settings.initialControlPoints);
}

// A 1 m rope (0.1 kg/m, EA = 100 kN: static stretch 1e-5, no bending) hanging from a pin at its top:
// with z the height above the free end, the transverse modes are J0(2 omega sqrt(z / g)), and the pin
// at z = L gives omega_k = (j_{0,k} / 2) sqrt(g / L) (j_{0,k} the zeros of J0).
RodSettings hangingSettings() {
  RodSettings settings;
  settings.restLength = 1.0;
  settings.linearDensity = 0.1;
  settings.youngsModulus = 1e5 / settings.area();
  settings.bendingStiffness = 0.0;
  return settings;  // default adaptivity
}

TEST(AdaptiveDynamics, HangingRopeKeepsItsFirstThreeBesselModesAndCoarsensWhenStill) {
  const RodSettings settings = hangingSettings();
  const double g = 9.81, length = 1.0;
  const double zeros[3] = {2.404825557695773, 5.520078110286311, 8.653727912911013};
  const double h = 1.0 / 2000;
  for (int k = 1; k <= 3; ++k) {
    const double omega = 0.5 * zeros[k - 1] * std::sqrt(g / length);
    const double exact = omega / (2.0 * kPi);
    Rod rod = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(0, -length, 0));
    rod.pin(rod.beginParameter());
    auto shape = [omega, g, length](double s) {
      return std::cyl_bessel_j(0.0, 2.0 * omega * std::sqrt(std::max(0.0, length - s) / g));
    };
    // 1 mm amplitude at the free end.
    setModeVelocity(rod, shape, Vec3::UnitX(), 1e-3 * omega);
    const ModeRun run = measureMode(rod, shape, Vec3::UnitX(), h, 7.0 / k);
    const double error = run.frequency / exact - 1.0;
    std::printf("[adaptive hanging rope] mode %d: f %.5f Hz (exact %.5f), error %+.2e, control points %d..%d\n", k,
                run.frequency, exact, error, run.minPoints, run.maxPoints);
    // Issue target 1 %; measured with the default criterion within 4.3e-3 (fixed 16: 0.42 %).
    EXPECT_LT(std::abs(error), 8e-3) << "mode " << k;
  }
  // Hanging straight and still: coarsened below the uniform count.
  Rod still = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(0, -length, 0));
  still.pin(still.beginParameter());
  for (int i = 0; i < 2000; ++i) ASSERT_TRUE(still.step(h).ok);
  std::printf("[adaptive hanging rope] still: %d control points (uniform %d)\n", still.controlPointCount(),
              settings.initialControlPoints);
  EXPECT_LT(still.controlPointCount(), settings.initialControlPoints);
}

}  // namespace
}  // namespace rope
