// SPDX-License-Identifier: MIT
#include "demos/ropesim/run_scene.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "demos/scenes/hang_scene.h"
#include "demos/scenes/knot_scene.h"
#include "render/video_writer.h"
#include "support/json_value.h"

namespace rope::demos {
namespace {

std::filesystem::path scratch(const std::string& name) {
  const auto directory = std::filesystem::temp_directory_path() / "splinerope_run_scene_test";
  std::filesystem::create_directories(directory);
  return directory / name;
}

std::string readFile(const std::filesystem::path& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// ropesim's --stats of `scene` simulated without rendering for `seconds` at 10 frames per second.
rope::test::JsonValue statsOfRun(const std::string& scene, const std::string& seconds) {
  const std::filesystem::path stats = scratch(scene + ".json");
  runScene(parseRopesimOptions(
      {scene, "--no-render", "--seconds", seconds, "--fps", "10", "--quiet", "--stats", stats.string()}));
  return rope::test::parseJson(readFile(stats));
}

// The --stats numbers must agree with the same scene simulated here, step by step.
TEST(RunScene, StatsJsonAgreesWithTheSimulation) {
  const rope::test::JsonValue json = statsOfRun("hang", "2");

  HangScene reference(HangSceneSettings{});
  double maxStrain = 0.0;
  long insertions = 0, removals = 0;
  const int steps = 480;
  for (int i = 0; i < steps; ++i) {
    const StepMeasurements m = reference.step();
    maxStrain = std::max(maxStrain, m.maxStrain);
    insertions += m.insertions;
    removals += m.removals;
  }
  EXPECT_EQ(json["scene"].string, "hang");
  EXPECT_DOUBLE_EQ(json["steps"].number, steps);
  EXPECT_NEAR(json["simulated_seconds"].number, 2.0, 1e-9);
  EXPECT_DOUBLE_EQ(json["control_points"]["final"].number, reference.rod().controlPointCount());
  EXPECT_DOUBLE_EQ(json["insertions"].number, insertions);
  EXPECT_DOUBLE_EQ(json["removals"].number, removals);
  EXPECT_NEAR(json["max_strain"].number, maxStrain, 1e-9 * maxStrain);
  EXPECT_TRUE(json["render_fps"].isNull());
  EXPECT_TRUE(json["max_penetration_m"].isNull());
  EXPECT_GT(json["step_time_us"]["median"].number, 0.0);
  EXPECT_GE(json["step_time_us"]["p95"].number, json["step_time_us"]["median"].number);
  const auto& frames = json["frames"];
  ASSERT_EQ(frames["t"].array.size(), 20u);  // 2 s at 10 fps
  EXPECT_NEAR(frames["sag_m"].array.back().number, reference.sag(), 0.01);
}

// The self-contact figures of the knot scene (the main job) agree with the simulation too.
TEST(RunScene, KnotStatsReportSelfOverlapAndTheKnotSeries) {
  const rope::test::JsonValue json = statsOfRun("knot", "1");

  KnotScene reference(KnotSceneSettings{});
  double maxOverlap = 0.0, maxPenetration = 0.0, lastFrameKnotLength = 0.0;
  int lastFrameContacts = 0;
  const int steps = 240;
  for (int i = 1; i <= steps; ++i) {
    const StepMeasurements m = reference.step();
    maxOverlap = std::max(maxOverlap, *m.maxSelfOverlap);
    maxPenetration = std::max(maxPenetration, *m.maxPenetration);
    if (i == 216) {  // the last frame is at t = 0.9 s (frames at 0, 0.1, ..., 0.9 s)
      lastFrameKnotLength = reference.knot().length;
      lastFrameContacts = reference.rope().lastStep().ropeContacts;
    }
  }
  EXPECT_EQ(json["scene"].string, "knot");
  EXPECT_DOUBLE_EQ(json["steps"].number, steps);
  ASSERT_FALSE(json["max_self_overlap_m"].isNull());
  EXPECT_GT(maxOverlap, 0.0);  // the knot's strands touch within the first second
  EXPECT_NEAR(json["max_self_overlap_m"].number, maxOverlap, 1e-9 * maxOverlap);  // 10 digits in the JSON
  EXPECT_NEAR(json["max_penetration_m"].number, maxPenetration, 1e-9 * maxPenetration);
  EXPECT_DOUBLE_EQ(json["control_points"]["final"].number, reference.rope().rod().controlPointCount());
  const auto& frames = json["frames"];
  ASSERT_EQ(frames["t"].array.size(), 10u);
  EXPECT_NEAR(frames["knot_length_m"].array.back().number, lastFrameKnotLength, 1e-9 * lastFrameKnotLength);
  EXPECT_DOUBLE_EQ(frames["self_contacts"].array.back().number, lastFrameContacts);
}

// The acceptance check of the video: H.264, yuv420p, the requested fps and size, and exactly
// seconds x fps frames, as ffprobe reports them.
TEST(RunScene, WritesAPlayableVideoWithTheRequestedFrames) {
  if (render::findExecutable("ffprobe").empty()) GTEST_SKIP() << "ffprobe not installed";
  const auto video = scratch("hang.mp4");
  std::filesystem::remove(video);
  RopesimOptions options = parseRopesimOptions({"hang", "--seconds", "1", "--fps", "12", "--size", "320x240",
                                                "--quiet", "--out", video.string()});
  const RunStatistics statistics = runScene(options);
  EXPECT_EQ(statistics.steps(), 240);
  const std::string command = "ffprobe -v error -select_streams v:0 -count_frames -show_entries "
                              "stream=codec_name,pix_fmt,width,height,r_frame_rate,nb_read_frames "
                              "-of default=noprint_wrappers=1 '" + video.string() + "'";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buffer[256];
  while (fgets(buffer, sizeof buffer, pipe) != nullptr) output += buffer;
  ASSERT_EQ(pclose(pipe), 0) << output;
  for (const char* expected : {"codec_name=h264", "pix_fmt=yuv420p", "width=320", "height=240",
                               "r_frame_rate=12/1", "nb_read_frames=12"}) {
    EXPECT_NE(output.find(expected), std::string::npos) << expected << " not in\n" << output;
  }
}

}  // namespace
}  // namespace rope::demos
