// SPDX-License-Identifier: MIT
#include "demos/ropesim/options.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace rope::demos {
namespace {

RopesimOptions parse(std::vector<std::string> arguments) { return parseRopesimOptions(arguments); }

// The message must name the option and the offending value.
void expectRejected(std::vector<std::string> arguments, const std::string& mentions1, const std::string& mentions2) {
  try {
    parse(arguments);
    FAIL() << "accepted " << mentions1 << " " << mentions2;
  } catch (const std::invalid_argument& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find(mentions1), std::string::npos) << what;
    EXPECT_NE(what.find(mentions2), std::string::npos) << what;
  }
}

TEST(RopesimOptions, NoArgumentsMeansHelp) { EXPECT_TRUE(parse({}).help); }

TEST(RopesimOptions, DefaultsRenderTheSceneToItsOwnVideo) {
  const RopesimOptions options = parse({"hang"});
  EXPECT_EQ(options.scene, "hang");
  ASSERT_TRUE(options.video.has_value());
  EXPECT_EQ(*options.video, "hang.mp4");
  EXPECT_EQ(options.width, 1280);
  EXPECT_EQ(options.height, 720);
  EXPECT_EQ(options.framesPerSecond, 30);
  EXPECT_TRUE(options.render);
  EXPECT_FALSE(options.seconds.has_value());
}

TEST(RopesimOptions, ReadsEveryOption) {
  const RopesimOptions options = parse({"tractrix", "--out", "a.mp4", "--frames", "dir", "--seconds", "2.5",
                                        "--fps", "24", "--size", "640x360", "--stats", "s.json", "--quiet"});
  EXPECT_EQ(*options.video, "a.mp4");
  EXPECT_EQ(*options.framesDirectory, "dir");
  EXPECT_DOUBLE_EQ(*options.seconds, 2.5);
  EXPECT_EQ(options.framesPerSecond, 24);
  EXPECT_EQ(options.width, 640);
  EXPECT_EQ(options.height, 360);
  EXPECT_EQ(*options.statsFile, "s.json");
  EXPECT_TRUE(options.quiet);
}

TEST(RopesimOptions, FramesOnlyWritesNoVideo) {
  const RopesimOptions options = parse({"hang", "--frames", "dir"});
  EXPECT_FALSE(options.video.has_value());
}

TEST(RopesimOptions, NoRenderWritesNothing) {
  const RopesimOptions options = parse({"hang", "--no-render"});
  EXPECT_FALSE(options.render);
  EXPECT_FALSE(options.video.has_value());
}

TEST(RopesimOptions, RejectsBadInputNamingOptionAndValue) {
  expectRejected({"nosuchscene"}, "scene", "nosuchscene");
  expectRejected({"hang", "--fps", "0"}, "--fps", "0");
  expectRejected({"hang", "--fps", "12x"}, "--fps", "12x");
  expectRejected({"hang", "--seconds", "nan"}, "--seconds", "nan");
  expectRejected({"hang", "--seconds", "-1"}, "--seconds", "-1");
  expectRejected({"hang", "--size", "641x360"}, "--size", "641x360");
  expectRejected({"hang", "--size", "640"}, "--size", "640");
  expectRejected({"hang", "--bogus"}, "--bogus", "unknown");
  expectRejected({"hang", "--out"}, "--out", "needs a value");
  expectRejected({"hang", "tractrix"}, "scene", "tractrix");
  expectRejected({"hang", "--no-render", "--out", "x.mp4"}, "--no-render", "--out");
  expectRejected({"--fps", "30"}, "scene", "missing");
}

TEST(RopesimOptions, UsageListsEveryScene) {
  const std::string usage = ropesimUsage();
  for (const char* scene : {"hang", "tractrix"}) EXPECT_NE(usage.find(scene), std::string::npos) << scene;
  for (const char* option : {"--out", "--frames", "--seconds", "--fps", "--size", "--no-render", "--stats", "--help"}) {
    EXPECT_NE(usage.find(option), std::string::npos) << option;
  }
}

}  // namespace
}  // namespace rope::demos
