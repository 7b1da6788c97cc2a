// SPDX-License-Identifier: MIT
#include "demos/ropesim/run_statistics.h"

#include <gtest/gtest.h>

#include "support/json_value.h"

namespace rope::demos {
namespace {

TEST(Quantile, InterpolatesBetweenOrderStatistics) {
  EXPECT_DOUBLE_EQ(quantile({}, 0.5), 0.0);
  EXPECT_DOUBLE_EQ(quantile({3.0, 1.0, 2.0}, 0.5), 2.0);
  EXPECT_DOUBLE_EQ(quantile({4.0, 1.0, 2.0, 3.0}, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(quantile({0.0, 10.0}, 0.95), 9.5);
}

TEST(RunStatistics, JsonCarriesEveryFieldWithTheAccumulatedValues) {
  RunStatistics statistics("hang");
  StepMeasurements a;
  a.controlPoints = 8;
  a.insertions = 2;
  a.maxStrain = 0.01;
  a.series = {{"sag_m", 0.3}};
  StepMeasurements b = a;
  b.controlPoints = 5;
  b.insertions = 0;
  b.removals = 3;
  b.maxStrain = 0.02;
  b.maxPenetration = 0.001;
  b.series = {{"sag_m", 0.31}};
  statistics.addFrame(0.0, StepMeasurements{});
  statistics.addStep(a, 10.0, 0.5);
  statistics.addStep(b, 30.0, 1.0);
  statistics.addFrame(1.0, b);
  statistics.setRenderFramesPerSecond(42.0);

  const rope::test::JsonValue json = rope::test::parseJson(statistics.toJson());
  EXPECT_EQ(json["scene"].string, "hang");
  EXPECT_DOUBLE_EQ(json["simulated_seconds"].number, 1.0);
  EXPECT_DOUBLE_EQ(json["steps"].number, 2);
  EXPECT_DOUBLE_EQ(json["step_time_us"]["median"].number, 20.0);
  EXPECT_DOUBLE_EQ(json["step_time_us"]["p95"].number, 29.0);
  EXPECT_DOUBLE_EQ(json["control_points"]["min"].number, 5);
  EXPECT_DOUBLE_EQ(json["control_points"]["max"].number, 8);
  EXPECT_DOUBLE_EQ(json["control_points"]["final"].number, 5);
  EXPECT_DOUBLE_EQ(json["insertions"].number, 2);
  EXPECT_DOUBLE_EQ(json["removals"].number, 3);
  EXPECT_DOUBLE_EQ(json["max_penetration_m"].number, 0.001);
  EXPECT_TRUE(json["max_self_overlap_m"].isNull());  // never measured: null, not zero
  EXPECT_DOUBLE_EQ(json["max_strain"].number, 0.02);
  EXPECT_DOUBLE_EQ(json["render_fps"].number, 42.0);
  const auto& frames = json["frames"];
  ASSERT_EQ(frames["t"].array.size(), 2u);
  EXPECT_DOUBLE_EQ(frames["t"].array[1].number, 1.0);
  EXPECT_DOUBLE_EQ(frames["control_points"].array[1].number, 5);
  EXPECT_DOUBLE_EQ(frames["max_strain"].array[1].number, 0.02);
  // A series first seen at the second frame still lines up with the frames: null where missing.
  ASSERT_EQ(frames["sag_m"].array.size(), 2u);
  EXPECT_TRUE(frames["sag_m"].array[0].isNull());
  EXPECT_DOUBLE_EQ(frames["sag_m"].array[1].number, 0.31);
}

TEST(RunStatistics, SceneNamesAreEscaped) {
  RunStatistics statistics("a\"b\\c");
  EXPECT_EQ(rope::test::parseJson(statistics.toJson())["scene"].string, "a\"b\\c");
}

}  // namespace
}  // namespace rope::demos
