// SPDX-License-Identifier: MIT
#pragma once
// The ropesim run loop, separate from main() so that tests can run it: simulate a scene for the
// requested time, render frames at the requested rate into a video and/or PNG files, and measure.

#include <vector>

#include "demos/ropesim/options.h"
#include "demos/ropesim/run_statistics.h"
#include "demos/scene_file/scene_checks.h"

namespace rope::demos {

// Runs options.scene: a scene file (options.sceneFile), a built-in scene shipped as a file
// (built_in_scene_files.h) or a scene built in C++. Throws SceneFileError for a bad scene file
// (before simulating) and std::runtime_error (simulation failure, ffmpeg missing or failing,
// unwritable files) with a message for the user. The checks of a scene file, evaluated, go to
// *checks if given (and to options.junitFile).
RunStatistics runScene(const RopesimOptions& options, std::vector<CheckResult>* checks = nullptr);

}  // namespace rope::demos
