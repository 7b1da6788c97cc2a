// SPDX-License-Identifier: MIT
#include "support/json_value.h"

#include <cctype>
#include <cstdlib>
#include <stdexcept>

namespace rope::test {

namespace {

class Parser {
 public:
  explicit Parser(const std::string& text) : text_(text) {}

  JsonValue document() {
    JsonValue value = parseValue();
    skipSpace();
    if (position_ != text_.size()) fail("trailing characters");
    return value;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("JSON: " + what + " at byte " + std::to_string(position_));
  }
  void skipSpace() {
    while (position_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[position_]))) ++position_;
  }
  char peek() {
    skipSpace();
    if (position_ >= text_.size()) fail("unexpected end");
    return text_[position_];
  }
  void expect(char c) {
    if (peek() != c) fail(std::string("expected '") + c + "'");
    ++position_;
  }
  bool literal(const char* word) {
    const std::string w(word);
    if (text_.compare(position_, w.size(), w) != 0) return false;
    position_ += w.size();
    return true;
  }

  JsonValue parseValue() {
    JsonValue value;
    const char c = peek();
    if (c == '{') {
      value.type = JsonValue::Type::Object;
      ++position_;
      if (peek() == '}') {
        ++position_;
        return value;
      }
      for (;;) {
        const std::string key = parseString();
        expect(':');
        value.object[key] = parseValue();
        if (peek() == ',') {
          ++position_;
          continue;
        }
        expect('}');
        return value;
      }
    }
    if (c == '[') {
      value.type = JsonValue::Type::Array;
      ++position_;
      if (peek() == ']') {
        ++position_;
        return value;
      }
      for (;;) {
        value.array.push_back(parseValue());
        if (peek() == ',') {
          ++position_;
          continue;
        }
        expect(']');
        return value;
      }
    }
    if (c == '"') {
      value.type = JsonValue::Type::String;
      value.string = parseString();
      return value;
    }
    if (literal("null")) return value;
    if (literal("true") || literal("false")) {
      value.type = JsonValue::Type::Boolean;
      value.boolean = text_[position_ - 1] == 'e' && text_[position_ - 2] == 'u';
      return value;
    }
    const char* begin = text_.c_str() + position_;
    char* end = nullptr;
    value.number = std::strtod(begin, &end);
    if (end == begin) fail("expected a value");
    position_ += static_cast<std::size_t>(end - begin);
    value.type = JsonValue::Type::Number;
    return value;
  }

  std::string parseString() {
    expect('"');
    std::string out;
    while (position_ < text_.size() && text_[position_] != '"') {
      char c = text_[position_++];
      if (c == '\\') {
        if (position_ >= text_.size()) fail("unterminated escape");
        c = text_[position_++];
        if (c == 'u') {
          if (position_ + 4 > text_.size()) fail("short \\u escape");
          out += static_cast<char>(std::strtol(text_.substr(position_, 4).c_str(), nullptr, 16));
          position_ += 4;
          continue;
        }
        if (c == 'n') c = '\n';
        if (c == 't') c = '\t';
      }
      out += c;
    }
    expect('"');
    return out;
  }

  const std::string& text_;
  std::size_t position_ = 0;
};

}  // namespace

const JsonValue& JsonValue::operator[](const std::string& key) const {
  if (type != Type::Object) throw std::out_of_range("JSON value is not an object (key " + key + ")");
  const auto found = object.find(key);
  if (found == object.end()) throw std::out_of_range("JSON object has no key " + key);
  return found->second;
}

JsonValue parseJson(const std::string& text) { return Parser(text).document(); }

}  // namespace rope::test
