// SPDX-License-Identifier: MIT
#include "demos/ropesim/options.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "demos/scenes/demo_scene.h"

namespace rope::demos {

namespace {

[[noreturn]] void fail(const std::string& option, const std::string& value, const std::string& reason) {
  throw std::invalid_argument(option + " " + value + ": " + reason);
}

int parseInteger(const std::string& option, const std::string& text, int low, int high) {
  std::size_t used = 0;
  long value = 0;
  try {
    value = std::stol(text, &used);
  } catch (const std::exception&) {
    fail(option, text, "expected a whole number");
  }
  if (used != text.size()) fail(option, text, "expected a whole number");
  if (value < low || value > high) {
    fail(option, text, "must be in " + std::to_string(low) + ".." + std::to_string(high));
  }
  return static_cast<int>(value);
}

double parsePositive(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    fail(option, text, "expected a number");
  }
  if (used != text.size() || !std::isfinite(value) || !(value > 0.0)) {
    fail(option, text, "expected a finite number > 0");
  }
  return value;
}

}  // namespace

RopesimOptions parseRopesimOptions(const std::vector<std::string>& arguments) {
  RopesimOptions options;
  if (arguments.empty()) {
    options.help = true;
    return options;
  }
  std::size_t first = 0;
  if (arguments[0] == "run") {
    if (arguments.size() < 2 || arguments[1].empty() || arguments[1][0] == '-') {
      fail("run", "", "needs a scene file: ropesim run FILE.json [options]");
    }
    options.sceneFile = arguments[1];
    const std::string& file = arguments[1];
    const std::size_t slash = file.find_last_of('/');
    std::string stem = slash == std::string::npos ? file : file.substr(slash + 1);
    if (stem.size() > 5 && stem.compare(stem.size() - 5, 5, ".json") == 0) stem.resize(stem.size() - 5);
    options.scene = stem;
    first = 2;
  }
  for (std::size_t i = first; i < arguments.size(); ++i) {
    const std::string& argument = arguments[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= arguments.size()) fail(argument, "", "needs a value");
      return arguments[++i];
    };
    if (argument == "--help" || argument == "-h") {
      options.help = true;
    } else if (argument == "--out") {
      options.video = value();
    } else if (argument == "--frames") {
      options.framesDirectory = value();
    } else if (argument == "--seconds") {
      options.seconds = parsePositive(argument, value());
    } else if (argument == "--fps") {
      options.framesPerSecond = parseInteger(argument, value(), 1, 240);
    } else if (argument == "--size") {
      const std::string& size = value();
      const std::size_t x = size.find('x');
      if (x == std::string::npos) fail(argument, size, "expected WIDTHxHEIGHT, e.g. 1280x720");
      options.width = parseInteger(argument, size.substr(0, x), 16, 8192);
      options.height = parseInteger(argument, size.substr(x + 1), 16, 8192);
      if (options.width % 2 != 0 || options.height % 2 != 0) {
        fail(argument, size, "width and height must be even (H.264 with yuv420p)");
      }
    } else if (argument == "--no-render") {
      options.render = false;
    } else if (argument == "--stats") {
      options.statsFile = value();
    } else if (argument == "--set" && options.sceneFile) {
      options.overrides.push_back(value());
    } else if (argument == "--junit" && options.sceneFile) {
      options.junitFile = value();
    } else if (argument == "--snapshot-on-failure" && options.sceneFile) {
      options.snapshotDirectory = value();
    } else if (argument == "--no-checks" && options.sceneFile) {
      options.checks = false;
    } else if (argument == "--quiet") {
      options.quiet = true;
    } else if (!argument.empty() && argument[0] == '-') {
      fail(argument, "", options.sceneFile || (argument != "--set" && argument != "--junit" && argument != "--no-checks" &&
                                                  argument != "--snapshot-on-failure")
                             ? "unknown option (see --help)"
                             : "only with `ropesim run FILE.json`");
    } else if (options.sceneFile) {
      fail("run", argument, "only one scene file per run");
    } else if (options.scene.empty()) {
      if (findScene(argument) == nullptr) fail("scene", argument, "unknown scene (see --help)");
      options.scene = argument;
    } else {
      fail("scene", argument, "only one scene per run");
    }
  }
  if (!options.help && options.scene.empty()) fail("scene", "", "missing (see --help)");
  if (!options.render && (options.video || options.framesDirectory)) {
    fail("--no-render", "", "cannot be combined with --out or --frames");
  }
  if (options.snapshotDirectory && !options.checks) {
    fail("--snapshot-on-failure", *options.snapshotDirectory, "needs the checks (drop --no-checks)");
  }
  if (options.render && !options.video && !options.framesDirectory) {
    options.video = options.scene + ".mp4";
  }
  return options;
}

std::string ropesimUsage() {
  std::ostringstream text;
  text << "usage: ropesim <scene> [options]\n"
          "       ropesim run FILE.json [--set PATH=VALUE]... [--junit FILE.xml] [--no-checks] [options]\n\n"
          "Runs a SplineRope scene, renders it headless (OSMesa) and writes an H.264 video.\n"
          "`run` reads the scene from a scene file (docs/scene-files.md) and evaluates its checks: exit\n"
          "status 0 when every check holds, 1 when one fails, 2 for a bad file or command line.\n\n"
          "scenes:\n";
  for (const SceneEntry& entry : sceneCatalogue()) {
    text << "  " << entry.name << std::string(entry.name.size() < 10 ? 10 - entry.name.size() : 1, ' ')
         << entry.description << " (" << entry.defaultSeconds << " s)\n";
  }
  text << "\noptions:\n"
          "  --out FILE.mp4     video output (default: <scene>.mp4)\n"
          "  --frames DIR       also write every frame as DIR/frame_00000.png ...\n"
          "  --seconds S        simulated seconds (default: the scene's)\n"
          "  --fps N            frames per second of the video (default 30)\n"
          "  --size WxH         frame size in pixels, even numbers (default 1280x720)\n"
          "  --no-render        simulate and measure only\n"
          "  --stats FILE.json  write run statistics as one JSON object\n"
          "  --quiet            no progress output\n"
          "  --set PATH=VALUE   run: override a key of the file, e.g. ropes[0].settings.youngsModulus=1e8\n"
          "  --junit FILE.xml   run: write the checks as a JUnit XML report\n"
          "  --no-checks        run: do not evaluate the file's checks\n"
          "  --snapshot-on-failure DIR  run: a PNG of each check's first failing moment, marked\n"
          "  --help             this text\n";
  return text.str();
}

}  // namespace rope::demos
