// SPDX-License-Identifier: MIT
#pragma once
// The built-in scenes that are scene files (demos/scenes/<name>.json): `ropesim <name>` runs them
// from the file, so the format is used and not only offered, and a test checks that each file gives
// bitwise the trajectory of its C++ builder.

#include <optional>
#include <string>
#include <vector>

namespace rope::demos {

// Names of the built-in scenes shipped as files.
const std::vector<std::string>& builtInSceneFileNames();
// The file of a built-in scene, or nullopt if that scene is built in C++ only.
std::optional<std::string> builtInSceneFile(const std::string& name);
// The directory holding them: share/SplineRope/scenes beside an installed ropesim, else the source
// tree's demos/scenes.
std::string builtInSceneDirectory();

}  // namespace rope::demos
