// SPDX-License-Identifier: MIT
#pragma once
// The ropesim run loop, separate from main() so that tests can run it: simulate a scene for the
// requested time, render frames at the requested rate into a video and/or PNG files, and measure.

#include "demos/ropesim/options.h"
#include "demos/ropesim/run_statistics.h"

namespace rope::demos {

// Runs options.scene. Throws std::runtime_error (simulation failure, ffmpeg missing or failing,
// unwritable files) with a message for the user.
RunStatistics runScene(const RopesimOptions& options);

}  // namespace rope::demos
