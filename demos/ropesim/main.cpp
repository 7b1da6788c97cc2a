// SPDX-License-Identifier: MIT
// ropesim: run, render and measure a SplineRope scene from the command line (see --help).
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "demos/ropesim/options.h"
#include "demos/ropesim/run_scene.h"

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
  try {
    const RunStatistics statistics = runScene(options);
    std::printf("%s: %ld steps, step time median %.1f us (p95 %.1f us), %d control points at the end, "
                "max strain %.3g\n",
                options.scene.c_str(), statistics.steps(), statistics.stepTimeMedian(),
                statistics.stepTimeP95(), statistics.finalControlPoints(), statistics.maxStrain());
    if (options.video) std::printf("video: %s\n", options.video->c_str());
    if (options.framesDirectory) std::printf("frames: %s\n", options.framesDirectory->c_str());
    if (options.statsFile) std::printf("statistics: %s\n", options.statsFile->c_str());
  } catch (const std::exception& error) {
    std::fprintf(stderr, "ropesim: %s\n", error.what());
    return 1;
  }
  return 0;
}
