// SPDX-License-Identifier: MIT
#include "rope/rod/coupled_solve.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "rope/common/error.h"
#include "rope/spline/bspline_basis.h"
#include "tests/rope/rod/rod_test_util.h"

namespace rope {
namespace {

RodSettings settingsFor(int points) {
  RodSettings settings;
  settings.restLength = 1.0;
  settings.linearDensity = 0.05;
  settings.youngsModulus = 1e7;
  settings.initialControlPoints = points;
  settings.adaptive = false;  // keep the knots, so trials can be compared point by point
  return settings;
}

// A bent, moving rod: positions and velocities off the straight line so every term is exercised.
Rod bentRod(int points, const Vec3& offset, unsigned seed) {
  Rod rod = Rod::fromSegment(settingsFor(points), offset, offset + Vec3(1.1, 0.0, 0.0));
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  PointList q = rod.controlPoints();
  PointList v = q;
  for (size_t i = 0; i < q.size(); ++i) {
    q[i] += Vec3(jitter(random), jitter(random), jitter(random));
    v[i] = 10.0 * Vec3(jitter(random), jitter(random), jitter(random));
  }
  rod.setControlPoints(q);
  rod.setVelocities(v);
  return rod;
}

Eigen::Matrix3d randomAdmittance(std::mt19937& random, double scale) {
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  Eigen::Matrix3d root;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) root(r, c) = entry(random);
  return scale * root * root.transpose();
}

struct TwoRods {
  Rod a = bentRod(9, Vec3(0, 0, 0), 1);
  Rod b = bentRod(12, Vec3(0, 0.02, 0.01), 2);
  std::vector<PointCoupling> couplings;
  std::vector<CouplingLaw> laws;
  TwoRods() {
    a.pin(a.beginParameter());                        // pins must keep holding under the coupling
    b.pin(0.5 * b.endParameter(), Vec3(0.6, 0.05, 0));  // and a moving pin target
    couplings = {{0, 0.3, 1, 0.31}, {0, 0.8, 1, 0.2}, {1, 0.1, 1, 0.9}, {0, 0.55, 0, 0.95}};
    std::mt19937 random(7);
    std::uniform_real_distribution<double> entry(-0.01, 0.01);
    for (size_t k = 0; k < couplings.size(); ++k) {
      CouplingLaw law;
      law.impulse = Vec3(entry(random), entry(random), entry(random));
      law.admittance = randomAdmittance(random, 0.02 * static_cast<double>(k + 1));
      laws.push_back(law);
    }
  }
  // Solves both trials and the couplings' impulses; the caller applies them.
  static constexpr double kStep = 1.0 / 240.0;
  ::testing::AssertionResult solve(CoupledSolve& solver, std::vector<Vec3>& impulses) {
    if (!a.solveTrial(kStep).ok || !b.solveTrial(kStep).ok) return ::testing::AssertionFailure() << "trial failed";
    solver.prepare({&a, &b}, couplings);
    if (!solver.solveImpulses(laws, impulses)) return ::testing::AssertionFailure() << "impulses failed";
    return ::testing::AssertionSuccess();
  }
};

TEST(CoupledSolve, CorrectionIsExactlyTheResponseToTheImpulses) {
  TwoRods setup;
  const double h = TwoRods::kStep;
  CoupledSolve solve;
  std::vector<Vec3> impulses;
  ASSERT_TRUE(setup.solve(solve, impulses));
  solve.apply(impulses);

  // The same impulses given to the rods as ordinary loads, solved directly: identical end state.
  Rod directA = setup.a, directB = setup.b;
  directA.clearLoads();
  directB.clearLoads();
  for (size_t k = 0; k < setup.couplings.size(); ++k) {
    const PointCoupling& c = setup.couplings[k];
    (c.rodA == 0 ? directA : directB).addImpulse(c.sA, impulses[k]);
    (c.rodB == 0 ? directA : directB).addImpulse(c.sB, -impulses[k]);
  }
  ASSERT_TRUE(directA.solveTrial(h).ok);
  ASSERT_TRUE(directB.solveTrial(h).ok);
  const PointList& va = setup.a.trialVelocities();
  const PointList& vb = setup.b.trialVelocities();
  for (size_t i = 0; i < va.size(); ++i) EXPECT_LT((va[i] - directA.trialVelocities()[i]).norm(), 1e-11) << i;
  for (size_t i = 0; i < vb.size(); ++i) EXPECT_LT((vb[i] - directB.trialVelocities()[i]).norm(), 1e-11) << i;
}

TEST(CoupledSolve, ImpulsesSatisfyTheirLawAtTheEndOfTheStep) {
  TwoRods setup;
  const double h = TwoRods::kStep;
  CoupledSolve solve;
  std::vector<Vec3> impulses;
  ASSERT_TRUE(setup.solve(solve, impulses));
  std::vector<Vec3> predicted, solved;
  for (int k = 0; k < solve.size(); ++k) predicted.push_back(solve.relativeChange(k, impulses));
  for (int k = 0; k < solve.size(); ++k) solved.push_back(solve.solvedRelativeChange(k));
  solve.apply(impulses);
  const Rod* rods[2] = {&setup.a, &setup.b};
  for (size_t k = 0; k < setup.couplings.size(); ++k) {
    const PointCoupling& c = setup.couplings[k];
    const Rod& a = *rods[c.rodA];
    const Rod& b = *rods[c.rodB];
    // w_new - w measured on the corrected trials ...
    const Vec3 change = (a.trialVelocity(c.sA) - a.velocity(c.sA)) - (b.trialVelocity(c.sB) - b.velocity(c.sB));
    EXPECT_LT((change - predicted[k]).norm(), 1e-11 * (1.0 + change.norm())) << k;
    // The same prediction through the rods' velocity change (one pass per solve) instead of Z's blocks.
    EXPECT_LT((change - solved[k]).norm(), 1e-11 * (1.0 + change.norm())) << k;
    // ... is what the law asked for: p = e - W (w_new - w).
    const Vec3 law = setup.laws[k].impulse - setup.laws[k].admittance * change;
    EXPECT_LT((impulses[k] - law).norm(), 1e-12) << k;
    EXPECT_GT(impulses[k].norm(), 1e-5) << "coupling " << k << " does nothing: the test would be vacuous";
  }
  // The pins still hold exactly at the end of the step.
  const Pin& pinA = setup.a.pins()[0];
  EXPECT_LT((setup.a.position(pinA.parameter) + h * setup.a.trialVelocity(pinA.parameter) - pinA.target).norm(), 1e-12);
  const Pin& pinB = setup.b.pins()[0];
  EXPECT_LT((setup.b.position(pinB.parameter) + h * setup.b.trialVelocity(pinB.parameter) - pinB.target).norm(), 1e-12);
}

TEST(CoupledSolve, ConservesMomentumBetweenFreeRods) {
  Rod a = bentRod(10, Vec3(0, 0, 0), 3);
  Rod b = bentRod(10, Vec3(0, 0.01, 0), 4);
  const double h = 1.0 / 120.0;
  ASSERT_TRUE(a.solveTrial(h).ok);
  ASSERT_TRUE(b.solveTrial(h).ok);
  const auto trialMomentum = [](const Rod& rod) {
    Rod copy = rod;
    copy.commitTrial();
    return copy.momentum();
  };
  const Vec3 before = trialMomentum(a) + trialMomentum(b);
  CoupledSolve solve;
  solve.prepare({&a, &b}, {{0, 0.5, 1, 0.5}, {0, 0.2, 1, 0.7}, {0, 0.1, 0, 0.9}});
  std::mt19937 random(11);
  std::vector<CouplingLaw> laws(3);
  for (CouplingLaw& law : laws) {
    law.impulse = Vec3(0.01, -0.02, 0.005);
    law.admittance = randomAdmittance(random, 1.0);  // stiff against the rods' mass (0.05 kg)
  }
  std::vector<Vec3> impulses;
  ASSERT_TRUE(solve.solveImpulses(laws, impulses));
  solve.apply(impulses);
  const Vec3 after = trialMomentum(a) + trialMomentum(b);
  EXPECT_LT((after - before).norm(), 1e-13) << "before " << before.transpose() << " after " << after.transpose();
  // The coupling did move each rod on its own.
  EXPECT_GT((trialMomentum(a) - trialMomentum(b)).norm(), 1e-4);
}

TEST(CoupledSolve, StiffSpringStopsTheRelativeMotion) {
  // W -> infinity along n is a rigid normal constraint: the relative normal velocity change cancels
  // the approach (e = 0 means "no force at the start state").
  Rod a = bentRod(10, Vec3(0, 0, 0), 5);
  Rod b = bentRod(10, Vec3(0, 0.01, 0), 6);
  const double h = 1.0 / 240.0;
  ASSERT_TRUE(a.solveTrial(h).ok);
  ASSERT_TRUE(b.solveTrial(h).ok);
  CoupledSolve solve;
  solve.prepare({&a, &b}, {{0, 0.5, 1, 0.5}});
  const Vec3 n(0, 1, 0);
  CouplingLaw law;
  law.admittance = 1e9 * n * n.transpose();
  std::vector<Vec3> impulses;
  ASSERT_TRUE(solve.solveImpulses({law}, impulses));
  EXPECT_LT(std::abs(n.dot(solve.relativeChange(0, impulses))), 1e-8 * (1.0 + solve.trialRelativeChange(0).norm()));
  EXPECT_GT(std::abs(n.dot(solve.trialRelativeChange(0))), 1e-3);
}

// solvedRelativeChange answers for the last solve's impulses: after a second solve with other laws
// it is that solve's relativeChange, and with no coupling acting it is the trial's own change.
TEST(CoupledSolve, SolvedRelativeChangeFollowsTheLastSolve) {
  TwoRods setup;
  CoupledSolve solve;
  std::vector<Vec3> impulses;
  ASSERT_TRUE(setup.solve(solve, impulses));
  for (int k = 0; k < solve.size(); ++k) {
    const Vec3 expected = solve.relativeChange(k, impulses);
    EXPECT_LT((solve.solvedRelativeChange(k) - expected).norm(), 1e-12 * (1.0 + expected.norm())) << k;
  }
  std::vector<CouplingLaw> other = setup.laws;
  other[0] = CouplingLaw{};
  other[1].admittance *= 3.0;
  ASSERT_TRUE(solve.solveImpulses(other, impulses));
  for (int k = 0; k < solve.size(); ++k) {
    const Vec3 expected = solve.relativeChange(k, impulses);
    EXPECT_LT((solve.solvedRelativeChange(k) - expected).norm(), 1e-12 * (1.0 + expected.norm())) << k;
    EXPECT_GT((solve.solvedRelativeChange(k) - solve.trialRelativeChange(k)).norm(), 0.0) << k;
  }
  const std::vector<CouplingLaw> none(other.size());
  ASSERT_TRUE(solve.solveImpulses(none, impulses));
  for (int k = 0; k < solve.size(); ++k) EXPECT_EQ(solve.solvedRelativeChange(k), solve.trialRelativeChange(k)) << k;
  // A new prepare forgets the last solve's impulses.
  ASSERT_TRUE(setup.solve(solve, impulses));
  solve.prepare({&setup.a, &setup.b}, setup.couplings);
  for (int k = 0; k < solve.size(); ++k) EXPECT_EQ(solve.solvedRelativeChange(k), solve.trialRelativeChange(k)) << k;
  // A coupling index outside the couplings is refused, naming it.
  for (const int k : {-1, solve.size()}) {
    try {
      solve.solvedRelativeChange(k);
      ADD_FAILURE() << "k = " << k << " accepted";
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.parameter(), "k") << e.what();
    }
  }
}

// The three-axis response (one pass over the factor) is bitwise the one-axis response, pins included.
TEST(CoupledSolve, ThreeAxisResponsesAreTheSingleAxisOnesBitwise) {
  TwoRods setup;
  for (Rod* rod : {&setup.a, &setup.b}) {
    ASSERT_TRUE(rod->solveTrial(TwoRods::kStep).ok);
    const size_t n3 = static_cast<size_t>(3 * rod->controlPointCount());
    for (const double s : {rod->beginParameter(), 0.37 * rod->endParameter(), rod->endParameter()}) {
      std::vector<double> together(3 * n3, std::numeric_limits<double>::quiet_NaN());
      rod->trialImpulseResponses(s, together.data());
      for (int axis = 0; axis < 3; ++axis) {
        std::vector<double> single(n3);
        rod->trialImpulseResponse(s, axis, single.data());
        for (size_t i = 0; i < n3; ++i) {
          EXPECT_EQ(std::memcmp(&single[i], &together[static_cast<size_t>(axis) * n3 + i], sizeof(double)), 0)
              << "s " << s << " axis " << axis << " entry " << i;
        }
      }
    }
  }
}

// The onward responses are the full ones, bit for bit, on the rows from the point's first control
// point on, pins included.
TEST(CoupledSolve, OnwardResponsesAreTheFullOnesFromThePointOn) {
  TwoRods setup;
  for (Rod* rod : {&setup.a, &setup.b}) {
    ASSERT_TRUE(rod->solveTrial(TwoRods::kStep).ok);
    const size_t n3 = static_cast<size_t>(3 * rod->controlPointCount());
    for (const double s : {rod->beginParameter(), 0.37 * rod->endParameter(), rod->endParameter()}) {
      std::vector<double> full(3 * n3), onward(3 * n3, std::numeric_limits<double>::quiet_NaN());
      rod->trialImpulseResponses(s, full.data());
      rod->trialImpulseResponsesOnward(s, onward.data());
      const size_t first = static_cast<size_t>(3 * (rod->knots().findSpan(s) - rod->degree()));
      for (size_t axis = 0; axis < 3; ++axis) {
        for (size_t i = first; i < n3; ++i) {
          EXPECT_EQ(std::memcmp(&full[axis * n3 + i], &onward[axis * n3 + i], sizeof(double)), 0)
              << "s " << s << " axis " << axis << " entry " << i;
        }
      }
    }
  }
}

// One impulse shared out over several points: with one point of weight 1 the single-point response
// bit for bit; with two (a coupling within one rod: +1 and -1.5 here) the weighted sum of theirs to
// round-off, on the rows from the earlier point's first control point on. Bad input names the field.
TEST(CoupledSolve, SharedImpulseResponsesAreTheWeightedSinglePointOnes) {
  TwoRods setup;
  for (Rod* rod : {&setup.a, &setup.b}) {
    ASSERT_TRUE(rod->solveTrial(TwoRods::kStep).ok);
    const size_t n3 = static_cast<size_t>(3 * rod->controlPointCount());
    const double s[2] = {0.21 * rod->endParameter(), 0.74 * rod->endParameter()};
    const double one = 1.0, weights[2] = {1.0, -1.5};
    std::vector<double> single(3 * n3), shared(3 * n3), later(3 * n3);
    rod->trialImpulseResponsesOnward(s[0], single.data());
    rod->trialImpulseResponsesOnward(&s[0], &one, 1, shared.data());
    const size_t first = static_cast<size_t>(3 * (rod->knots().findSpan(s[0]) - rod->degree()));
    for (size_t axis = 0; axis < 3; ++axis) {
      for (size_t i = first; i < n3; ++i) {
        ASSERT_EQ(std::memcmp(&single[axis * n3 + i], &shared[axis * n3 + i], sizeof(double)), 0) << axis << ", " << i;
      }
    }
    rod->trialImpulseResponses(s[1], later.data());
    rod->trialImpulseResponsesOnward(s, weights, 2, shared.data());
    double scale = 0.0;
    for (const double x : single) scale = std::max(scale, std::abs(x));
    for (size_t axis = 0; axis < 3; ++axis) {
      for (size_t i = first; i < n3; ++i) {
        const double expected = weights[0] * single[axis * n3 + i] + weights[1] * later[axis * n3 + i];
        ASSERT_NEAR(shared[axis * n3 + i], expected, 1e-12 * scale) << axis << ", " << i;
      }
    }
    const auto expectField = [&](const char* field, const double* points, const double* w, int count) {
      try {
        rod->trialImpulseResponsesOnward(points, w, count, shared.data());
        ADD_FAILURE() << field << " accepted";
      } catch (const InvalidArgument& e) {
        EXPECT_EQ(e.parameter(), field) << e.what();
      }
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double offRod[2] = {s[0], rod->endParameter() + 1.0}, notANumber[2] = {s[0], nan};
    const double infinite[2] = {std::numeric_limits<double>::infinity(), 1.0};
    expectField("count", s, weights, 0);
    expectField("count", s, weights, Rod::kMaxResponsePoints + 1);
    expectField("s[1]", offRod, weights, 2);
    expectField("s[1]", notANumber, weights, 2);
    expectField("weights[0]", s, infinite, 2);
    EXPECT_TRUE(rod->hasTrial());
  }
}

// Z blocks are cached per step: a second pass with other laws predicts what a fresh solve predicts.
TEST(CoupledSolve, RepeatedPassesPredictWhatAFreshSolvePredicts) {
  TwoRods setup;
  CoupledSolve solve;
  std::vector<Vec3> impulses;
  ASSERT_TRUE(setup.solve(solve, impulses));
  std::vector<CouplingLaw> other = setup.laws;
  other[1] = CouplingLaw{};  // one coupling released, another stiffer
  other[2].admittance *= 3.0;
  ASSERT_TRUE(solve.solveImpulses(other, impulses));
  CoupledSolve fresh;
  fresh.prepare({&setup.a, &setup.b}, setup.couplings);
  std::vector<Vec3> freshImpulses;
  ASSERT_TRUE(fresh.solveImpulses(other, freshImpulses));
  for (int k = 0; k < solve.size(); ++k) {
    const Vec3 again = solve.relativeChange(k, impulses), once = fresh.relativeChange(k, freshImpulses);
    EXPECT_EQ(std::memcmp(again.data(), once.data(), sizeof(double) * 3), 0) << k;
    EXPECT_EQ(std::memcmp(impulses[static_cast<size_t>(k)].data(), freshImpulses[static_cast<size_t>(k)].data(),
                          sizeof(double) * 3), 0) << k;
  }
  // And back to the first laws (each coupling's law square root is kept between passes while its law
  // is unchanged): the bits of the first solve.
  std::vector<Vec3> first;
  ASSERT_TRUE(fresh.solveImpulses(setup.laws, first));
  ASSERT_TRUE(solve.solveImpulses(setup.laws, impulses));
  CoupledSolve firstOnly;
  firstOnly.prepare({&setup.a, &setup.b}, setup.couplings);
  std::vector<Vec3> firstOnlyImpulses;
  ASSERT_TRUE(firstOnly.solveImpulses(setup.laws, firstOnlyImpulses));
  for (int k = 0; k < solve.size(); ++k) {
    const size_t u = static_cast<size_t>(k);
    EXPECT_EQ(std::memcmp(impulses[u].data(), firstOnlyImpulses[u].data(), sizeof(double) * 3), 0) << k;
    EXPECT_EQ(std::memcmp(first[u].data(), firstOnlyImpulses[u].data(), sizeof(double) * 3), 0) << k;
  }
}

TEST(CoupledSolve, RejectsBadInputAndLeavesRodsAlone) {
  Rod a = bentRod(8, Vec3(0, 0, 0), 8);
  EXPECT_THROW(
      {
        try {
          CoupledSolve().prepare({&a}, {{0, 0.1, 0, 0.9}});
        } catch (const InvalidArgument& e) {
          EXPECT_EQ(e.parameter(), "rods[0]");  // no trial yet
          throw;
        }
      },
      InvalidArgument);
  ASSERT_TRUE(a.solveTrial(0.01).ok);
  const test::RodSnapshot before(a);
  const auto expectParameter = [&](const std::vector<PointCoupling>& couplings, const std::string& name) {
    try {
      CoupledSolve().prepare({&a}, couplings);
      ADD_FAILURE() << "accepted " << name;
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.parameter(), name);
    }
  };
  expectParameter({{1, 0.1, 0, 0.9}}, "couplings[0].rodA");
  expectParameter({{0, 0.1, 0, 0.9}, {0, 0.1, -1, 0.9}}, "couplings[1].rodB");
  expectParameter({{0, 1.5, 0, 0.9}}, "couplings[0].sA");
  expectParameter({{0, 0.1, 0, std::numeric_limits<double>::quiet_NaN()}}, "couplings[0].sB");
  expectParameter({{0, 0.4, 0, 0.4}}, "couplings[0].sB");
  EXPECT_TRUE(test::sameState(before, test::RodSnapshot(a)));
  EXPECT_TRUE(a.hasTrial());

  CoupledSolve solve;
  solve.prepare({&a}, {{0, 0.1, 0, 0.9}});
  std::vector<Vec3> impulses;
  CouplingLaw bad;
  bad.admittance(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(solve.solveImpulses({bad}, impulses));  // reported, not propagated
  EXPECT_THROW(solve.solveImpulses({}, impulses), InvalidArgument);
}

TEST(RodSplitStep, StepEqualsTrialThenCommitBitwise) {
  Rod stepped = bentRod(12, Vec3(0, 1, 0), 9);
  stepped.pin(0.0);
  Rod split = stepped;
  for (int i = 0; i < 20; ++i) {
    stepped.addForce(0.7, Vec3(0.1, 0.2, 0.0));
    split.addForce(0.7, Vec3(0.1, 0.2, 0.0));
    const StepReport a = stepped.step(1.0 / 240.0);
    const StepReport trial = split.solveTrial(1.0 / 240.0);
    ASSERT_TRUE(trial.ok);
    EXPECT_TRUE(split.hasTrial());
    const StepReport b = split.commitTrial();
    EXPECT_FALSE(split.hasTrial());
    EXPECT_EQ(a.insertions, b.insertions);
    ASSERT_TRUE(test::sameState(test::RodSnapshot(stepped), test::RodSnapshot(split))) << "step " << i;
  }
}

TEST(RodSplitStep, TrialLeavesTheRodUnchangedAndChangesInvalidateIt) {
  Rod rod = bentRod(8, Vec3(0, 0, 0), 10);
  const test::RodSnapshot before(rod);
  ASSERT_TRUE(rod.solveTrial(0.01).ok);
  EXPECT_TRUE(test::sameState(before, test::RodSnapshot(rod)));
  EXPECT_NE(rod.trialVelocities()[3], rod.velocities()[3]);  // gravity acted in the trial
  rod.addForce(0.5, Vec3(1, 0, 0));  // a new load makes the trial stale
  EXPECT_FALSE(rod.hasTrial());
  EXPECT_THROW(rod.commitTrial(), InvalidArgument);
  EXPECT_THROW(rod.trialVelocities(), InvalidArgument);
  std::vector<double> response(static_cast<size_t>(3 * rod.controlPointCount()));
  std::vector<double> responses(3 * response.size());
  EXPECT_THROW(rod.trialImpulseResponse(0.5, 0, response.data()), InvalidArgument);
  EXPECT_THROW(rod.trialImpulseResponsesOnward(0.5, responses.data()), InvalidArgument);
  ASSERT_TRUE(rod.solveTrial(0.01).ok);
  // Both three-axis forms name a parameter off the rod or not a number, and keep the trial.
  for (const double s : {-0.1, 2.0, std::numeric_limits<double>::quiet_NaN()}) {
    for (const bool onward : {false, true}) {
      try {
        onward ? rod.trialImpulseResponsesOnward(s, responses.data()) : rod.trialImpulseResponses(s, responses.data());
        ADD_FAILURE() << "accepted s = " << s << (onward ? " (onward)" : "");
      } catch (const InvalidArgument& e) {
        EXPECT_EQ(e.parameter(), "s") << e.what();
      }
    }
  }
  EXPECT_TRUE(rod.hasTrial());
  EXPECT_THROW(rod.trialImpulseResponse(0.5, 3, response.data()), InvalidArgument);
  EXPECT_THROW(rod.trialImpulseResponse(2.0, 0, response.data()), InvalidArgument);
  EXPECT_THROW(rod.markInteraction(-1.0), InvalidArgument);
  EXPECT_THROW(rod.trialVelocity(std::numeric_limits<double>::quiet_NaN()), InvalidArgument);
  const auto expectH = [&rod](double h) {
    try {
      rod.solveTrial(h);
      ADD_FAILURE() << "accepted h = " << h;
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.parameter(), "h");
    }
  };
  expectH(0.0);
  expectH(-0.01);
  expectH(std::numeric_limits<double>::quiet_NaN());
  rod.clearLoads();
  EXPECT_FALSE(rod.hasTrial());
  EXPECT_TRUE(test::sameState(before, test::RodSnapshot(rod)));
}

// The response to an impulse along any direction is the same combination of the three axis
// responses (the system is linear), from one solve; a bad direction is refused by name.
TEST(RodSplitStep, ImpulseResponseAlongADirectionCombinesTheAxes) {
  Rod rod = bentRod(9, Vec3(0, 0, 0), 4);
  rod.pin(rod.beginParameter());
  ASSERT_TRUE(rod.solveTrial(1.0 / 240.0).ok);
  const size_t size = static_cast<size_t>(3 * rod.controlPointCount());
  const Vec3 direction(0.3, -1.7, 0.8);
  const double s = 0.37 * rod.endParameter();
  std::vector<double> along(size), axis(size), combined(size, 0.0);
  rod.trialImpulseResponse(s, direction, along.data());
  for (int c = 0; c < 3; ++c) {
    rod.trialImpulseResponse(s, c, axis.data());
    for (size_t i = 0; i < size; ++i) combined[i] += direction[c] * axis[i];
  }
  double scale = 0.0;
  for (const double x : combined) scale = std::max(scale, std::abs(x));
  ASSERT_GT(scale, 0.0);
  for (size_t i = 0; i < size; ++i) EXPECT_NEAR(along[i], combined[i], 1e-13 * scale) << "entry " << i;
  try {
    rod.trialImpulseResponse(s, Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0), along.data());
    ADD_FAILURE() << "accepted a NaN direction";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.parameter(), "direction[0]");
  }
}

TEST(RodSplitStep, MarkedInteractionGetsAKnot) {
  RodSettings settings = settingsFor(8);
  settings.adaptive = true;
  Rod rod = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(1, 0, 0));
  rod.pin(0.0);
  ASSERT_TRUE(rod.solveTrial(0.01).ok);
  rod.markInteraction(0.4321);
  const StepReport report = rod.commitTrial();
  EXPECT_EQ(rod.knots().multiplicity(0.4321), 1);
  EXPECT_GE(report.insertions, 1);
}

// A coupling that acts marks both its points as interaction points (a knot there at commit), unless
// it is flagged as a quadrature sample of a distributed contact (interaction = false).
TEST(CoupledSolve, OnlyInteractionCouplingsGetKnots) {
  for (const bool interaction : {true, false}) {
    RodSettings settings = settingsFor(8);
    settings.adaptive = true;
    Rod a = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(1, 0, 0));
    Rod b = Rod::fromSegment(settings, Vec3(0, 0.01, 0), Vec3(1, 0.01, 0));
    a.pin(0.0);
    b.pin(0.0);
    ASSERT_TRUE(a.solveTrial(0.01).ok);
    ASSERT_TRUE(b.solveTrial(0.01).ok);
    PointCoupling coupling{0, 0.4321, 1, 0.6543};
    coupling.interaction = interaction;
    CoupledSolve solve;
    solve.prepare({&a, &b}, {coupling});
    CouplingLaw law;
    law.impulse = Vec3(0, 1e-3, 0);
    std::vector<Vec3> impulses;
    ASSERT_TRUE(solve.solveImpulses({law}, impulses));
    solve.apply(impulses);
    a.commitTrial();
    b.commitTrial();
    EXPECT_EQ(a.knots().multiplicity(0.4321), interaction ? 1 : 0) << "interaction " << interaction;
    EXPECT_EQ(b.knots().multiplicity(0.6543), interaction ? 1 : 0) << "interaction " << interaction;
  }
}

// A generalised impulse that is the sum of two curve-point impulses, b(s_k) d_k, gets the sum of
// their responses from one solve (what the sliding-bound GMRES products rely on); without a trial
// or with a non-finite entry it is refused by name, the input untouched in the latter case.
TEST(RodSplitStep, GeneralizedResponseIsTheSumOfThePointResponses) {
  Rod rod = bentRod(9, Vec3(0, 0, 0), 4);
  rod.pin(rod.beginParameter());
  std::vector<double> impulses(static_cast<size_t>(3 * rod.controlPointCount()), 0.0);
  try {
    rod.trialGeneralizedResponse(impulses.data());
    ADD_FAILURE() << "answered without a trial";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.parameter(), "trial");
  }
  ASSERT_TRUE(rod.solveTrial(1.0 / 240.0).ok);
  const size_t size = impulses.size();
  const double s[2] = {0.23 * rod.endParameter(), 0.81 * rod.endParameter()};
  const Vec3 direction[2] = {Vec3(0.3, -1.7, 0.8), Vec3(-2.0, 0.1, 0.5)};
  std::vector<double> expected(size, 0.0), single(size);
  for (int k = 0; k < 2; ++k) {
    rod.trialImpulseResponse(s[k], direction[k], single.data());
    for (size_t i = 0; i < size; ++i) expected[i] += single[i];
    BasisValues basis;
    const int first = rod.knots().findSpan(s[k]) - rod.degree();
    evaluateBasis(rod.knots(), first + rod.degree(), s[k], 0, basis);
    for (int a = 0; a <= rod.degree(); ++a)
      for (int c = 0; c < 3; ++c)
        impulses[static_cast<size_t>(3 * (first + a) + c)] += basis.d[0][static_cast<size_t>(a)] * direction[k][c];
  }
  rod.trialGeneralizedResponse(impulses.data());
  double scale = 0.0;
  for (const double x : expected) scale = std::max(scale, std::abs(x));
  ASSERT_GT(scale, 0.0);
  for (size_t i = 0; i < size; ++i) EXPECT_NEAR(impulses[i], expected[i], 1e-13 * scale) << "entry " << i;
  // The pinned end does not move.
  for (size_t i = 0; i < 3; ++i) EXPECT_NEAR(impulses[i], 0.0, 1e-13 * scale);
  std::vector<double> bad(size, 0.0);
  bad[5] = std::numeric_limits<double>::infinity();
  try {
    rod.trialGeneralizedResponse(bad.data());
    ADD_FAILURE() << "accepted an infinite impulse";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.parameter(), "impulses");
  }
  EXPECT_EQ(bad[5], std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace rope
