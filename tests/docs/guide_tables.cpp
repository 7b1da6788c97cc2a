// SPDX-License-Identifier: MIT
#include "docs/guide_tables.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace rope::docs {

namespace {

constexpr double kPi = 3.14159265358979323846;
const std::string kDegreeSign = "\xC2\xB0";  // UTF-8 "°"

std::string trim(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  const auto end = text.find_last_not_of(" \t\r");
  return text.substr(begin, end - begin + 1);
}

// The cells of a table row "| a | b |" (pipes inside code spans do not split).
std::vector<std::string> splitRow(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  bool inCode = false;
  const std::string row = trim(line);
  for (std::size_t i = 1; i < row.size(); ++i) {
    const char c = row[i];
    if (c == '`') inCode = !inCode;
    if (c == '|' && !inCode) {
      cells.push_back(trim(cell));
      cell.clear();
    } else {
      cell += c;
    }
  }
  return cells;
}

// The first code span of a heading line, or "" if it has none.
std::string headingOwner(const std::string& line) {
  const auto open = line.find('`');
  if (open == std::string::npos) return "";
  const auto close = line.find('`', open + 1);
  return close == std::string::npos ? "" : line.substr(open + 1, close - open - 1);
}

// Recursive-descent evaluation of the value grammar (see guide_tables.h).
class Parser {
 public:
  Parser(const std::string& text, const Symbols& symbols) : text_(text), symbols_(symbols) {}

  double expression() {
    const double left = sum();
    if (!accept("<<")) return left;
    const double right = sum();
    return std::ldexp(left, static_cast<int>(right));
  }

  void expectEnd() {
    skipSpaces();
    if (at_ != text_.size()) fail("unexpected '" + text_.substr(at_) + "'");
  }
  bool accept(const std::string& token) {
    skipSpaces();
    if (text_.compare(at_, token.size(), token) != 0) return false;
    at_ += token.size();
    return true;
  }
  void expect(const std::string& token) {
    if (!accept(token)) fail("expected '" + token + "'");
  }
  [[noreturn]] void fail(const std::string& why) const {
    throw std::invalid_argument("'" + text_ + "': " + why);
  }

 private:
  double sum() {
    double value = product();
    while (true) {
      if (accept("+")) {
        value += product();
      } else if (accept("-")) {
        value -= product();
      } else {
        return value;
      }
    }
  }
  double product() {
    double value = unary();
    while (true) {
      if (accept("*")) {
        value *= unary();
      } else if (accept("/")) {
        value /= unary();
      } else {
        return value;
      }
    }
  }
  double unary() { return accept("-") ? -unary() : atom(); }
  double atom() {
    skipSpaces();
    if (accept("(")) {
      const double value = expression();
      expect(")");
      return value;
    }
    if (at_ < text_.size() && (std::isalpha(static_cast<unsigned char>(text_[at_])) || text_[at_] == '_')) {
      std::size_t end = at_;
      while (end < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[end])) || text_[end] == '_')) ++end;
      const std::string name = text_.substr(at_, end - at_);
      const auto found = symbols_.find(name);
      if (found == symbols_.end()) fail("unknown name '" + name + "'");
      at_ = end;
      return found->second;
    }
    const char* begin = text_.c_str() + at_;
    char* end = nullptr;
    const double value = std::strtod(begin, &end);
    if (end == begin) fail("expected a number");
    at_ += static_cast<std::size_t>(end - begin);
    return accept(kDegreeSign) ? value * (kPi / 180.0) : value;
  }
  void skipSpaces() {
    while (at_ < text_.size() && text_[at_] == ' ') ++at_;
  }

  const std::string& text_;
  const Symbols& symbols_;
  std::size_t at_ = 0;
};

// "a, b, c" up to the closing character, evaluated.
std::vector<double> list(Parser& parser, const std::string& close) {
  std::vector<double> values{parser.expression()};
  while (parser.accept(",")) values.push_back(parser.expression());
  parser.expect(close);
  return values;
}

}  // namespace

std::vector<GuideTable> readGuideTables(const std::string& path, const std::string& firstColumn) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error("cannot read " + path);
  const std::vector<std::string> header{firstColumn, "unit", "default", "range", "meaning"};
  std::vector<GuideTable> tables;
  std::string line, owner;
  bool inFence = false, inTable = false;
  for (int number = 1; std::getline(file, line); ++number) {
    const std::string text = trim(line);
    if (text.rfind("```", 0) == 0) inFence = !inFence;
    if (inFence) continue;
    if (inTable && text.rfind("|", 0) == 0) {
      if (text.rfind("|---", 0) == 0 || text.rfind("| ---", 0) == 0) continue;
      const std::vector<std::string> cells = splitRow(text);
      if (cells.size() != header.size()) {
        throw std::runtime_error(path + ":" + std::to_string(number) + ": expected " +
                                 std::to_string(header.size()) + " cells, found " + std::to_string(cells.size()));
      }
      tables.back().rows.push_back(GuideRow{number, cells[0], cells[1], cells[2], cells[3], cells[4]});
      continue;
    }
    inTable = false;
    if (text.rfind("#", 0) == 0) owner = headingOwner(text);
    if (text.rfind("|", 0) == 0 && splitRow(text) == header) {
      tables.push_back(GuideTable{owner, number, {}});
      inTable = true;
    }
  }
  return tables;
}

std::optional<std::string> leadingCode(const std::string& cell) {
  if (cell.empty() || cell[0] != '`') return std::nullopt;
  const auto close = cell.find('`', 1);
  if (close == std::string::npos) return std::nullopt;
  return cell.substr(1, close - 1);
}

double evaluate(const std::string& expression, const Symbols& symbols) {
  Parser parser(expression, symbols);
  const double value = parser.expression();
  parser.expectEnd();
  return value;
}

std::vector<double> evaluateTuple(const std::string& text, const Symbols& symbols) {
  Parser parser(text, symbols);
  parser.expect("(");
  const std::vector<double> values = list(parser, ")");
  parser.expectEnd();
  return values;
}

Range parseRange(const std::string& text, const Symbols& symbols) {
  Parser parser(text, symbols);
  Range range;
  if (parser.accept(">=")) {
    range.lower = Bound{parser.expression(), true};
  } else if (parser.accept(">")) {
    range.lower = Bound{parser.expression(), false};
  } else if (parser.accept("<=")) {
    range.upper = Bound{parser.expression(), true};
  } else if (parser.accept("<")) {
    range.upper = Bound{parser.expression(), false};
  } else if (parser.accept("!=")) {
    range.excluded = parser.expression();
  } else if (parser.accept("{")) {
    range.members = list(parser, "}");
  } else {
    const bool lowerInclusive = parser.accept("[");
    if (!lowerInclusive) parser.expect("(");
    const double lower = parser.expression();
    parser.expect(",");
    const double upper = parser.expression();
    const bool upperInclusive = parser.accept("]");
    if (!upperInclusive) parser.expect(")");
    range.lower = Bound{lower, lowerInclusive};
    range.upper = Bound{upper, upperInclusive};
  }
  parser.expectEnd();
  return range;
}

}  // namespace rope::docs
