// SPDX-License-Identifier: MIT
// ropesim: run, render and measure a SplineRope scene from the command line (see --help).
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "demos/ropesim/options.h"
#include "demos/ropesim/run_scene.h"
#include "demos/scene_file/scene_file_error.h"

int main(int argc, char** argv) {
  using namespace rope::demos;
  RopesimOptions options;
  try {
    options = parseRopesimOptions(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const std::exception& error) {
    std::fprintf(stderr, "ropesim: %s\n\n%s", error.what(), ropesimUsage().c_str());
    return 2;
  }
  if (options.help) {
    std::printf("%s", ropesimUsage().c_str());
    return 0;
  }
  std::vector<CheckResult> checks;
  try {
    const RunStatistics statistics = runScene(options, &checks);
    std::printf("%s: %ld steps, step time median %.1f us (p95 %.1f us), %d control points at the end, "
                "max strain %.3g\n",
                options.scene.c_str(), statistics.steps(), statistics.stepTimeMedian(),
                statistics.stepTimeP95(), statistics.finalControlPoints(), statistics.maxStrain());
    if (options.video) std::printf("video: %s\n", options.video->c_str());
    if (options.framesDirectory) std::printf("frames: %s\n", options.framesDirectory->c_str());
    if (options.statsFile) std::printf("statistics: %s\n", options.statsFile->c_str());
    if (options.junitFile) std::printf("JUnit report: %s\n", options.junitFile->c_str());
  } catch (const SceneFileError& error) {
    std::fprintf(stderr, "ropesim: %s: %s\n", options.sceneFile.value_or(options.scene).c_str(), error.what());
    return 2;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "ropesim: %s\n", error.what());
    return 1;
  }
  // The verdict of a scene file's checks: 0 when every one holds, 1 when one fails.
  int failed = 0;
  for (const CheckResult& check : checks) {
    std::printf("check %-40s %s\n", ("'" + check.name + "'").c_str(), check.message.c_str());
    if (!check.snapshot.empty()) std::printf("      snapshot of its first failure (t = %.6g s): %s\n", check.firstFailureTime, check.snapshot.c_str());
    failed += check.passed ? 0 : 1;
  }
  if (!checks.empty()) std::printf("%zu checks, %d failed\n", checks.size(), failed);
  return failed == 0 ? 0 : 1;
}
