// SPDX-License-Identifier: MIT
// [B] §4's planar experiment on paths of our own (the paper does not give its path): a 5 m straight
// object, 52 leading-end steps of 0.5 m, 6 initial sides, 140°/160°. Also the threshold/length-error
// relation on random paths. Results are printed and recorded as test properties.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "demos/scenes/arc_path.h"
#include "rope/common/error.h"
#include "rope/tractrix/length_angle.h"
#include "rope/tractrix/tractrix_rope.h"

namespace rope {
namespace {

const PointList kStraight = {Vec3(0, 0, 0), Vec3(-5, 0, 0)};  // leading end at the origin

constexpr double kPi = 3.14159265358979323846;
const demos::ArcPath kSBend = demos::sBendPath();
const demos::ArcPath kLoop = demos::loopPath();

struct PathRun {
  std::vector<int> counts;
  std::vector<double> errors;       // (L - L0)/L0 per step
  std::vector<double> gaps;         // (polygon - curve)/polygon per step, after adaptation
  std::vector<MergeRecord> merges;  // every merge of the run
  std::vector<int> mergeSteps;
  int maxCount = 0;
  double maxError = 0.0;
  double maxGap = 0.0;
  double maxMergeRelative = 0.0;  // largest merge error / initial length
};

PathRun runPath(const TractrixSettings& settings, const std::function<Vec3(int)>& target, int steps) {
  TractrixRope rope(kStraight, settings);
  PathRun run;
  for (int k = 1; k <= steps; ++k) {
    const TractrixStepReport& report = rope.moveLeadingEnd(target(k));
    EXPECT_EQ(report.merges, static_cast<int>(report.mergeRecords.size()));
    run.counts.push_back(report.controlPointCount);
    run.errors.push_back(report.lengthError);
    const double gap = (report.polygonLength - report.curveLength) / report.polygonLength;
    run.gaps.push_back(gap);
    run.maxCount = std::max(run.maxCount, report.controlPointCount);
    run.maxError = std::max(run.maxError, std::fabs(report.lengthError));
    run.maxGap = std::max(run.maxGap, gap);
    for (const MergeRecord& merge : report.mergeRecords) {
      run.merges.push_back(merge);
      run.mergeSteps.push_back(k);
      run.maxMergeRelative = std::max(run.maxMergeRelative, merge.chosenLengthError() / rope.initialLength());
    }
  }
  return run;
}

// [B] as published: no length correction.
TractrixSettings paperSettings(TractrixVariant variant) {
  TractrixSettings settings;  // 6 sides, cubic, 140°/160°
  settings.variant = variant;
  settings.lengthCorrection = TractrixLengthCorrection::kNone;
  return settings;
}

// The defaults: the same, plus the length correction (beyond [B]).
TractrixSettings correctedSettings(TractrixVariant variant) {
  TractrixSettings settings;
  settings.variant = variant;
  return settings;
}

void print(const char* name, const PathRun& run) {
  std::printf("%s: max count %d, max |length error| %.3f%%, merges %zu, largest merge error %.3f%%\n  count:",
              name, run.maxCount, 100 * run.maxError, run.merges.size(), 100 * run.maxMergeRelative);
  for (int c : run.counts) std::printf(" %d", c);
  std::printf("\n  error %%:");
  for (double e : run.errors) std::printf(" %.2f", 100 * e);
  std::printf("\n");
  for (size_t i = 0; i < run.merges.size(); ++i) {
    const MergeRecord& m = run.merges[i];
    std::printf("  merge at step %d, knot %.4f: length error %.3e m (other candidate %.3e m), shape error %.3e m\n",
                run.mergeSteps[i], m.parameter, m.chosenLengthError(), m.lengthError[1 - m.chosen],
                m.chosenShapeError());
  }
}

TEST(TractrixExperiment, PaperPlanarExperimentOnAnSBend) {
  auto target = [](int k) { return kSBend.at(0.5 * k); };
  const PathRun sd = runPath(paperSettings(TractrixVariant::kSplineSubdivide), target, 52);
  const PathRun mrg = runPath(paperSettings(TractrixVariant::kSplineSubdivideMerge), target, 52);
  TractrixSettings trxSettings = paperSettings(TractrixVariant::kPolyline);
  trxSettings.segmentCount = 20;
  const PathRun trx = runPath(trxSettings, target, 52);
  print("TRX (20 segments)", trx);
  print("TRX_SD", sd);
  print("TRX_SD_MRG", mrg);
  RecordProperty("trx_sd_max_control_points", sd.maxCount);
  RecordProperty("trx_sd_mrg_max_control_points", mrg.maxCount);
  RecordProperty("trx_sd_max_length_error_percent", std::to_string(100 * sd.maxError));
  RecordProperty("trx_sd_mrg_max_length_error_percent", std::to_string(100 * mrg.maxError));
  RecordProperty("trx_sd_mrg_largest_merge_error_percent", std::to_string(100 * mrg.maxMergeRelative));

  EXPECT_LT(trx.maxError, 1e-12);  // TRX keeps its length exactly
  // [B] §4: under 5% throughout with merging.
  for (size_t k = 0; k < mrg.errors.size(); ++k) EXPECT_LT(std::fabs(mrg.errors[k]), 0.05) << "step " << k + 1;
  // The count rises with the bending and falls back once the path straightens.
  EXPECT_GT(mrg.maxCount, 7);
  EXPECT_EQ(mrg.counts.back(), 7);
  EXPECT_GT(sd.maxCount, 7);
  EXPECT_GE(sd.maxCount, mrg.maxCount);
  EXPECT_GE(sd.counts.back(), sd.maxCount);  // subdivision only never comes back down
  // Every merge reports its own error, the chosen candidate's being the smaller one.
  ASSERT_FALSE(mrg.merges.empty());
  for (const MergeRecord& merge : mrg.merges) {
    EXPECT_TRUE(std::isfinite(merge.chosenLengthError()));
    EXPECT_LE(merge.chosenLengthError(), merge.lengthError[1 - merge.chosen]);
  }
  EXPECT_LT(mrg.maxMergeRelative, 0.018);  // [B] saw at most 1.8% from one merge
}

TEST(TractrixExperiment, HeavyLoopShowsTheLengthRatchet) {
  // A path that wraps the 5 m object around a 1.5 m loop. Subdivision never changes the curve but
  // shortens the polygon, and the tractrix then keeps that shorter polygon: each bend that gets
  // subdivided locks in part of the curve's shortfall. With 6 initial sides this path loses more
  // than [B]'s 5%; the bounds here hold the measured behaviour of the method as published.
  auto target = [](int k) { return kLoop.at(0.5 * k); };
  const PathRun sd = runPath(paperSettings(TractrixVariant::kSplineSubdivide), target, 52);
  const PathRun mrg = runPath(paperSettings(TractrixVariant::kSplineSubdivideMerge), target, 52);
  print("loop TRX_SD", sd);
  print("loop TRX_SD_MRG", mrg);
  RecordProperty("loop_trx_sd_max_control_points", sd.maxCount);
  RecordProperty("loop_trx_sd_mrg_max_control_points", mrg.maxCount);
  EXPECT_GT(sd.maxCount, 20);
  EXPECT_LT(mrg.maxCount, sd.maxCount);
  EXPECT_GT(mrg.maxCount, 12);
  EXPECT_EQ(mrg.counts.back(), 7);  // merging brings it back to the initial resolution
  EXPECT_LT(sd.maxError, 0.13);   // measured 11.84 %
  EXPECT_LT(mrg.maxError, 0.18);  // measured 16.82 %
  EXPECT_LT(mrg.maxMergeRelative, 0.018);
}

// Random leading-end walks: steps of 0.5 m turning by up to maxTurn (planar or in 3D).
std::function<Vec3(int)> randomWalk(unsigned seed, double maxTurn = kPi / 6) {
  auto state = std::make_shared<std::tuple<std::mt19937_64, Vec3, Vec3>>(std::mt19937_64(seed), Vec3(0, 1, 0),
                                                                         Vec3::Zero());
  const bool threeD = seed % 2 == 1;
  return [state, threeD, maxTurn](int) {
    auto& [rng, direction, position] = *state;
    std::uniform_real_distribution<double> turn(-maxTurn, maxTurn);
    const double a = turn(rng);
    direction = Vec3(std::cos(a) * direction.x() - std::sin(a) * direction.y(),
                     std::sin(a) * direction.x() + std::cos(a) * direction.y(), direction.z());
    if (threeD) {
      const double b = turn(rng);
      direction = Vec3(direction.x(), std::cos(b) * direction.y() - std::sin(b) * direction.z(),
                       std::sin(b) * direction.y() + std::cos(b) * direction.z());
    }
    direction.normalize();
    position += 0.5 * direction;
    return position;
  };
}

TEST(TractrixExperiment, CorrectedRopeKeepsItsLengthOnEveryPath) {
  // Beyond [B] (the target: within 1 % at every increment): the same paths with the default
  // length correction, on the S-bend, the loop, and random walks with tight loops (turns of up to 30°
  // and 60° per 0.5 m step). Every step ends at the initial length to the solver's tolerance.
  struct Case {  // each case makes a fresh path (the random walks carry their state)
    std::string name;
    std::function<std::function<Vec3(int)>()> make;
  };
  std::vector<Case> cases = {{"sbend", [] { return [](int k) { return kSBend.at(0.5 * k); }; }},
                             {"loop", [] { return [](int k) { return kLoop.at(0.5 * k); }; }}};
  for (unsigned seed = 0; seed < 12; ++seed) {
    cases.push_back({"walk30_" + std::to_string(seed), [seed] { return randomWalk(seed); }});
    cases.push_back({"walk60_" + std::to_string(seed), [seed] { return randomWalk(100 + seed, kPi / 3); }});
  }
  for (TractrixVariant variant : {TractrixVariant::kSplineSubdivide, TractrixVariant::kSplineSubdivideMerge}) {
    const char* name = variant == TractrixVariant::kSplineSubdivide ? "TRX_SD" : "TRX_SD_MRG";
    double worst = 0.0;
    for (const Case& c : cases) {
      const PathRun corrected = runPath(correctedSettings(variant), c.make(), 52);
      worst = std::max(worst, corrected.maxError);
      for (size_t k = 0; k < corrected.errors.size(); ++k) {
        ASSERT_LT(std::fabs(corrected.errors[k]), 1.5e-12) << name << " " << c.name << " step " << k + 1;
      }
    }
    const PathRun loopAsPublished = runPath(paperSettings(variant), [](int k) { return kLoop.at(0.5 * k); }, 52);
    const PathRun loopCorrected = runPath(correctedSettings(variant), [](int k) { return kLoop.at(0.5 * k); }, 52);
    std::printf("%s: loop max |length error| %.3f%% as published, %.2e corrected; worst over %zu paths %.2e\n", name,
                100 * loopAsPublished.maxError, loopCorrected.maxError, cases.size(), worst);
    RecordProperty(std::string(name) + "_corrected_worst_length_error", formatValue(worst));
    RecordProperty(std::string(name) + "_loop_length_error_as_published_percent",
                   std::to_string(100 * loopAsPublished.maxError));
    // The correction still adapts: the loop is subdivided, and merged back down with merging.
    EXPECT_GT(loopCorrected.maxCount, 12) << name;
    if (variant == TractrixVariant::kSplineSubdivideMerge) {
      EXPECT_EQ(loopCorrected.counts.back(), 7);
    }
  }
}

TEST(TractrixExperiment, TighterThresholdsNeverGiveALargerPolygonCurveGap) {
  // After each step's subdivision every corner is at or above the subdivision angle, so the
  // curve's shortfall against its polygon is bounded through the length-vs-angle relation (method §14)
  // and shrinks as the threshold tightens. Checked on random paths for TRX_SD, with the bound of
  // the "both angles equal" cubic piece at the subdivision angle.
  const double ladder[][2] = {{120, 150}, {130, 155}, {140, 160}, {150, 165}, {160, 170}, {170, 175}};
  for (unsigned seed = 0; seed < 24; ++seed) {
    double previous = 1.0;
    for (const auto& thresholds : ladder) {
      TractrixSettings settings = paperSettings(TractrixVariant::kSplineSubdivide);
      settings.setThresholdsDegrees(thresholds[0], thresholds[1]);
      const PathRun run = runPath(settings, randomWalk(seed), 52);
      EXPECT_LE(run.maxGap, previous) << "seed " << seed << " at " << thresholds[0] << "°";
      const double bound = pieceLengthShortfall(LengthAngleModel::kCubicBothAngles, degrees(thresholds[0]));
      EXPECT_LE(run.maxGap, bound) << "seed " << seed << " at " << thresholds[0] << "°";
      previous = run.maxGap;
    }
  }
}

}  // namespace
}  // namespace rope

namespace rope {
namespace {

// Issue 7's acceptance item "for random paths, a tighter threshold never gives a larger maximum
// error" does not hold for [B] as published (TractrixLengthCorrection::kNone): on the same 24 random
// walks and threshold ladder as above, the maximum |length error| over 52 steps rises on a tighter
// rung in many cases (measured: 43 of 120 rung pairs for TRX_SD, 64 of 120 for TRX_SD_MRG).
// Subdivision does not change the curve but shortens the polygon that the tractrix then keeps (the
// ratchet of HeavyLoopShowsTheLengthRatchet), so a tighter threshold that subdivides earlier can lock
// in more shortfall; with merging, tighter merging angles also merge later and differently. What does
// hold is the per-step polygon-curve gap (the test above), and, with the default length correction,
// the claim itself: every rung keeps the length to the solver's tolerance, so no rung is worse than
// another beyond round-off. The as-published table is printed and recorded, and its worst case held
// to its measured value.
TEST(TractrixExperiment, WithTheDefaultCorrectionNoThresholdLosesLength) {
  const double ladder[][2] = {{120, 150}, {130, 155}, {140, 160}, {150, 165}, {160, 170}, {170, 175}};
  for (TractrixVariant variant : {TractrixVariant::kSplineSubdivide, TractrixVariant::kSplineSubdivideMerge}) {
    const char* name = variant == TractrixVariant::kSplineSubdivide ? "TRX_SD" : "TRX_SD_MRG";
    int rises = 0;
    double largest = 0.0, largestCorrected = 0.0;
    for (unsigned seed = 0; seed < 24; ++seed) {
      std::printf("%s seed %2u max |length error| %% as published:", name, seed);
      double previous = 1.0;
      for (const auto& thresholds : ladder) {
        TractrixSettings settings = paperSettings(variant);
        settings.setThresholdsDegrees(thresholds[0], thresholds[1]);
        const PathRun run = runPath(settings, randomWalk(seed), 52);
        std::printf(" %.3f", 100 * run.maxError);
        if (run.maxError > previous) ++rises;
        previous = run.maxError;
        largest = std::max(largest, run.maxError);
        TractrixSettings corrected = correctedSettings(variant);
        corrected.setThresholdsDegrees(thresholds[0], thresholds[1]);
        const PathRun correctedRun = runPath(corrected, randomWalk(seed), 52);
        EXPECT_LT(correctedRun.maxError, 1.5e-12) << name << " seed " << seed << " at " << thresholds[0] << "°";
        largestCorrected = std::max(largestCorrected, correctedRun.maxError);
      }
      std::printf("\n");
    }
    std::printf("%s: as published, a tighter rung gave a larger maximum length error in %d of 120 cases (largest "
                "%.3f %%); corrected, the largest is %.2e\n", name, rises, 100 * largest, largestCorrected);
    RecordProperty(std::string(name) + "_tighter_rung_larger_max_error_cases", rises);
    RecordProperty(std::string(name) + "_largest_max_length_error_percent", std::to_string(100 * largest));
    RecordProperty(std::string(name) + "_largest_corrected_length_error", formatValue(largestCorrected));
    // Measured 12.82 % (TRX_SD) and 14.37 % (TRX_SD_MRG): the README's "10-22 % on tight loops".
    EXPECT_LT(largest, 0.15) << name;
  }
}

}  // namespace
}  // namespace rope
