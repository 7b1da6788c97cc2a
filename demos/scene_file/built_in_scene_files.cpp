// SPDX-License-Identifier: MIT
#include "demos/scene_file/built_in_scene_files.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

namespace rope::demos {

const std::vector<std::string>& builtInSceneFileNames() {
  static const std::vector<std::string> names = {"drape", "thinbar", "pile", "rest", "cut", "winch", "floorpull", "capstan", "crane"};
  return names;
}

std::string builtInSceneDirectory() {
  // An installed ropesim (bin/ropesim) finds them in share/SplineRope/scenes beside it; one in the
  // build tree in the source tree's demos/scenes.
  std::error_code error;
  const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    const std::filesystem::path installed = executable.parent_path() / ".." / "share" / "SplineRope" / "scenes";
    if (std::filesystem::is_directory(installed, error)) return installed.lexically_normal().string();
  }
  return SPLINEROPE_SCENE_DIRECTORY;
}

std::optional<std::string> builtInSceneFile(const std::string& name) {
  const std::vector<std::string>& names = builtInSceneFileNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) return std::nullopt;
  return builtInSceneDirectory() + "/" + name + ".json";
}

}  // namespace rope::demos
