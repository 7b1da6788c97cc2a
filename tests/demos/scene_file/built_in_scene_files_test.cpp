// SPDX-License-Identifier: MIT
// Every built-in scene shipped as a file (demos/scenes/<name>.json, which `ropesim <name>` runs)
// gives bitwise the same trajectory as the same scene built in C++ (its builder in demos/scenes),
// and its own checks hold.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>

#include "demos/scene_file/built_in_scene_files.h"
#include "demos/scene_file/file_scene.h"
#include "demos/scene_file/scene_file_reader.h"
#include "demos/scenes/demo_scene.h"

namespace rope::demos {
namespace {

class BuiltInSceneFile : public testing::TestWithParam<std::string> {};

TEST_P(BuiltInSceneFile, GivesTheBuildersTrajectoryBitForBit) {
  const std::string& name = GetParam();
  const SceneEntry* entry = findScene(name);
  ASSERT_NE(entry, nullptr);
  FileScene fromFile(readSceneFile(*builtInSceneFile(name)), false);
  const std::unique_ptr<DemoScene> built = entry->create();
  ASSERT_EQ(fromFile.timeStep(), built->timeStep());
  // About one simulated second (half for the pile, 7 ms a step): through the landing and the
  // contacts; the cut to 1.5 s, past the cut at 1 s; the winch to 7.5 s, through lowering, hold and
  // the start of the lift; the crane to 6 s, through its lift along a smoothstep from 3 s to 5 s.
  const int steps = name == "pile" ? 120 : name == "cut" ? 360 : name == "winch" ? 1800 : name == "crane" ? 1440 : 240;
  std::vector<double> a, b;
  for (int i = 1; i <= steps; ++i) {
    fromFile.step();
    built->step();
    if (i % 40 != 0 && i != steps) continue;
    a.clear();
    b.clear();
    fromFile.appendState(a);
    built->appendState(b);
    ASSERT_EQ(a.size(), b.size()) << "step " << i;
    ASSERT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0) << name << " differs at step " << i;
  }
}

TEST_P(BuiltInSceneFile, ChecksHoldOverTheDefaultRun) {
  const std::string& name = GetParam();
  if (name == "pile") GTEST_SKIP() << "6 s of the pile (10 s of wall time) run by demos_ropesim_scene_file_runs";
  FileScene scene(readSceneFile(*builtInSceneFile(name)));
  while (scene.time() < scene.description().duration - 0.5 * scene.timeStep()) scene.step();
  scene.finishChecks();
  ASSERT_FALSE(scene.checks().results().empty());
  for (const CheckResult& check : scene.checks().results()) EXPECT_TRUE(check.passed) << check.name << ": " << check.message;
}

INSTANTIATE_TEST_SUITE_P(Files, BuiltInSceneFile, testing::ValuesIn(builtInSceneFileNames()),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace rope::demos
