// SPDX-License-Identifier: MIT
#pragma once
// Command line of `ropesim <scene> [options]`.

#include <optional>
#include <string>
#include <vector>

namespace rope::demos {

struct RopesimOptions {
  std::string scene;                 // a name from sceneCatalogue(), or the scene file's name (run)
  std::optional<std::string> sceneFile;  // `ropesim run FILE.json`: the scene file (docs/scene-files.md)
  std::vector<std::string> overrides;    // run: --set PATH=VALUE, in order
  std::optional<std::string> junitFile;  // run: --junit FILE.xml
  bool checks = true;                    // run: --no-checks skips evaluating the file's checks
  std::optional<std::string> snapshotDirectory;  // run: --snapshot-on-failure DIR
  std::optional<std::string> video;  // --out FILE.mp4 (default: <scene>.mp4 unless --no-render or --frames)
  std::optional<std::string> framesDirectory;  // --frames DIR: one PNG per frame
  std::optional<double> seconds;     // --seconds S, simulated seconds (default: the scene's)
  int framesPerSecond = 30;          // --fps N, 1..240
  int width = 1280;                  // --size WxH, even, 16..8192
  int height = 720;
  bool render = true;                // --no-render: simulate and measure only
  std::optional<std::string> statsFile;  // --stats FILE.json
  bool quiet = false;                // --quiet: no progress output
  bool help = false;                 // --help, or no arguments at all
};

// Throws std::invalid_argument with a message naming the option and the offending value.
RopesimOptions parseRopesimOptions(const std::vector<std::string>& arguments);

// The help text, listing every scene.
std::string ropesimUsage();

}  // namespace rope::demos
