// SPDX-License-Identifier: MIT
#pragma once
// Reads and validates a scene file (docs/scene-files.md) into a SceneDescription. Everything is
// checked before anything is simulated: JSON syntax, types, unknown keys (with the nearest valid key
// suggested), ranges (the library's own validate(): RodSettings, BulletRopeSettings,
// AttachmentSettings, render::Camera) and references between objects (an attachment's body, a
// check's rope). The first problem throws SceneFileError naming the JSON path and the value.
// Whatever needs the built world (a parameter s outside its rope) is checked by FileScene's
// constructor, which throws the same error.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demos/scene_file/scene_description.h"
#include "demos/scene_file/scene_file_error.h"

namespace rope::demos {

// `--set PATH=VALUE`: replaces (or adds) the value at a JSON path such as
// `ropes[0].settings.youngsModulus` before the file is read. VALUE is JSON (1e8, true, "exact",
// [0, 1, 0]); text that is not JSON is taken as a string.
struct SceneOverride {
  std::string path;
  std::string value;
};
// Splits "PATH=VALUE"; throws SceneFileError for text without '='.
SceneOverride parseSceneOverride(const std::string& text);
// Applies overrides in order; a path through a missing array element or a non-object is an error.
void applySceneOverrides(nlohmann::json& document, const std::vector<SceneOverride>& overrides);

// Reads the file (and its overrides). Throws SceneFileError.
SceneDescription readSceneFile(const std::string& file, const std::vector<SceneOverride>& overrides = {});
// The same from JSON text (`file` only names it in messages).
SceneDescription readSceneText(const std::string& text, const std::string& file = "",
                               const std::vector<SceneOverride>& overrides = {});
SceneDescription readSceneJson(const nlohmann::json& document, const std::string& file = "");

}  // namespace rope::demos
