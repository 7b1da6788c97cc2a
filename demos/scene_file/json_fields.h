// SPDX-License-Identifier: MIT
#pragma once
// Typed access to one JSON object of a scene file, each error naming the JSON path and the value
// (SceneFileError). Internal to the scene-file reader.

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "rope/common/types.h"

namespace rope::demos {

// The value as the file writes it, shortened for messages.
std::string jsonText(const nlohmann::json& value);

class JsonFields {
 public:
  // Checks that `value` is an object whose keys are all in the key table `table` (scene_file_keys.h):
  // an unknown key is an error naming it, with the nearest valid key suggested.
  JsonFields(const nlohmann::json& value, std::string path, const std::string& table);

  const std::string& path() const { return path_; }
  std::string pathOf(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  bool has(const std::string& key) const;
  const nlohmann::json& at(const std::string& key) const;  // throws "missing" if absent

  // Each throws SceneFileError for a value of the wrong type (or a missing required key).
  double number(const std::string& key) const;  // required
  double number(const std::string& key, double fallback) const;
  int integer(const std::string& key, int fallback) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::string string(const std::string& key) const;  // required
  std::string string(const std::string& key, const std::string& fallback) const;
  Vec3 vec3(const std::string& key) const;  // required, [x, y, z]
  Vec3 vec3(const std::string& key, const Vec3& fallback) const;
  // A string out of `choices` (an empty fallback: the key is required); anything else is an error
  // that lists the choices.
  std::string choice(const std::string& key, const std::vector<std::string>& choices, const std::string& fallback) const;
  // An array (absent: empty); the items are returned with their paths "key[i]".
  std::vector<std::pair<const nlohmann::json*, std::string>> array(const std::string& key) const;

 private:
  void require(const std::string& key) const;
  const nlohmann::json& value_;
  std::string path_;
  std::string table_;
};

// Free forms of the same checks, for values not held in an object.
double jsonNumber(const nlohmann::json& value, const std::string& path);
Vec3 jsonVec3(const nlohmann::json& value, const std::string& path);

}  // namespace rope::demos
