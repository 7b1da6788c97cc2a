// SPDX-License-Identifier: MIT
#pragma once
// A small JSON reader for tests that check what our programs write (ropesim --stats). Strict:
// any syntax error throws std::runtime_error with the byte offset.

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace rope::test {

struct JsonValue {
  enum class Type { Null, Boolean, Number, String, Array, Object };
  Type type = Type::Null;
  bool boolean = false;
  double number = 0.0;
  std::string string;
  std::vector<JsonValue> array;
  std::map<std::string, JsonValue> object;

  // Object member; throws std::out_of_range naming the key if absent or if this is not an object.
  const JsonValue& operator[](const std::string& key) const;
  bool has(const std::string& key) const { return type == Type::Object && object.count(key) > 0; }
  bool isNull() const { return type == Type::Null; }
};

JsonValue parseJson(const std::string& text);

}  // namespace rope::test
