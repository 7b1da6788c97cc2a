// SPDX-License-Identifier: MIT
#include "demos/scene_file/built_in_scene_files.h"

#include <algorithm>

namespace rope::demos {

const std::vector<std::string>& builtInSceneFileNames() {
  static const std::vector<std::string> names = {"drape", "thinbar", "pile", "rest"};
  return names;
}

std::string builtInSceneDirectory() { return SPLINEROPE_SCENE_DIRECTORY; }

std::optional<std::string> builtInSceneFile(const std::string& name) {
  const std::vector<std::string>& names = builtInSceneFileNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) return std::nullopt;
  return builtInSceneDirectory() + "/" + name + ".json";
}

}  // namespace rope::demos
