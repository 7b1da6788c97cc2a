// SPDX-License-Identifier: MIT
#include "demos/scene_file/json_fields.h"

#include <cmath>

#include "demos/scene_file/scene_file_error.h"
#include "demos/scene_file/scene_file_keys.h"

namespace rope::demos {

std::string jsonText(const nlohmann::json& value) {
  std::string text = value.dump();
  constexpr std::size_t kLongest = 60;
  if (text.size() > kLongest) text = text.substr(0, kLongest - 3) + "...";
  return text;
}

namespace {

const char* typeName(const nlohmann::json& value) { return value.type_name(); }

}  // namespace

double jsonNumber(const nlohmann::json& value, const std::string& path) {
  if (!value.is_number()) {
    throw SceneFileError(path, jsonText(value), std::string("must be a number, not ") + typeName(value));
  }
  const double number = value.get<double>();
  if (!std::isfinite(number)) throw SceneFileError(path, jsonText(value), "must be finite");
  return number;
}

Vec3 jsonVec3(const nlohmann::json& value, const std::string& path) {
  if (!value.is_array() || value.size() != 3) {
    throw SceneFileError(path, jsonText(value), "must be an array of 3 numbers [x, y, z]");
  }
  return Vec3(jsonNumber(value[0], path + "[0]"), jsonNumber(value[1], path + "[1]"),
              jsonNumber(value[2], path + "[2]"));
}

JsonFields::JsonFields(const nlohmann::json& value, std::string path, const std::string& table)
    : value_(value), path_(std::move(path)), table_(table) {
  if (!value.is_object()) {
    throw SceneFileError(path_, jsonText(value), std::string("must be an object, not ") + typeName(value));
  }
  const std::vector<std::string>& keys = sceneFileKeys(table).keys;
  for (auto item = value.begin(); item != value.end(); ++item) {
    bool known = false;
    for (const std::string& key : keys) known = known || key == item.key();
    if (known) continue;
    const std::string nearest = nearestKey(item.key(), keys);
    throw SceneFileError(pathOf(item.key()), "",
                         "unknown key" + (nearest.empty() ? std::string(" (see docs/scene-files.md)")
                                                          : " (did you mean '" + nearest + "'?)"));
  }
}

bool JsonFields::has(const std::string& key) const { return value_.contains(key); }

void JsonFields::require(const std::string& key) const {
  if (!has(key)) throw SceneFileError(pathOf(key), "", "missing (required)");
}

const nlohmann::json& JsonFields::at(const std::string& key) const {
  require(key);
  return value_.at(key);
}

double JsonFields::number(const std::string& key) const { return jsonNumber(at(key), pathOf(key)); }

double JsonFields::number(const std::string& key, double fallback) const {
  return has(key) ? number(key) : fallback;
}

int JsonFields::integer(const std::string& key, int fallback) const {
  if (!has(key)) return fallback;
  const nlohmann::json& value = at(key);
  if (!value.is_number_integer()) {
    throw SceneFileError(pathOf(key), jsonText(value), "must be a whole number");
  }
  const auto number = value.get<long long>();
  if (number < -2147483648LL || number > 2147483647LL) {
    throw SceneFileError(pathOf(key), jsonText(value), "must fit a 32-bit integer");
  }
  return static_cast<int>(number);
}

bool JsonFields::boolean(const std::string& key, bool fallback) const {
  if (!has(key)) return fallback;
  const nlohmann::json& value = at(key);
  if (!value.is_boolean()) throw SceneFileError(pathOf(key), jsonText(value), "must be true or false");
  return value.get<bool>();
}

std::string JsonFields::string(const std::string& key) const {
  const nlohmann::json& value = at(key);
  if (!value.is_string()) throw SceneFileError(pathOf(key), jsonText(value), "must be a string");
  return value.get<std::string>();
}

std::string JsonFields::string(const std::string& key, const std::string& fallback) const {
  return has(key) ? string(key) : fallback;
}

Vec3 JsonFields::vec3(const std::string& key) const { return jsonVec3(at(key), pathOf(key)); }

Vec3 JsonFields::vec3(const std::string& key, const Vec3& fallback) const { return has(key) ? vec3(key) : fallback; }

std::string JsonFields::choice(const std::string& key, const std::vector<std::string>& choices,
                               const std::string& fallback) const {
  if (!has(key)) {
    if (fallback.empty()) require(key);
    return fallback;
  }
  const std::string text = string(key);
  std::string list;
  for (const std::string& c : choices) {
    if (c == text) return text;
    list += (list.empty() ? "" : ", ") + ("\"" + c + "\"");
  }
  throw SceneFileError(pathOf(key), jsonText(at(key)), "must be one of " + list);
}

std::vector<std::pair<const nlohmann::json*, std::string>> JsonFields::array(const std::string& key) const {
  std::vector<std::pair<const nlohmann::json*, std::string>> items;
  if (!has(key)) return items;
  const nlohmann::json& value = at(key);
  if (!value.is_array()) throw SceneFileError(pathOf(key), jsonText(value), "must be an array");
  for (std::size_t i = 0; i < value.size(); ++i) {
    items.emplace_back(&value[i], pathOf(key) + "[" + std::to_string(i) + "]");
  }
  return items;
}

}  // namespace rope::demos
