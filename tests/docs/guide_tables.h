// SPDX-License-Identifier: MIT
#pragma once
// Reading the settings tables of docs/user-guide.md for user_guide_test.cpp: the markdown tables
// `| field | unit | default | range | meaning |`, each owned by the first code span of the heading
// above it (`### \`rope::RodSettings\``), and the small grammar of the machine-readable cells: a
// default or a range written as a leading code span.
//
//   values:  1.0  1e-4  -1  1/60  140°  1 << 10  kMaxDegree  (0, -9.81, 0)  "veryfast"  true
//   ranges:  > 0   >= 0   != 0   [1, 8]   (0, 1]   [2, kMaxDegree]   {1, 2, 4, 8}

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace rope::docs {

struct GuideRow {
  int line = 0;  // 1-based line in the guide
  std::string field, unit, defaultValue, range, meaning;
};

struct GuideTable {
  std::string owner;  // the first code span of the nearest heading above the table
  int line = 0;       // of the header row
  std::vector<GuideRow> rows;
};

// Every table of the file whose header row is `| <firstColumn> | unit | default | range | meaning |`.
// Throws std::runtime_error for an unreadable file or a row with the wrong number of cells.
std::vector<GuideTable> readGuideTables(const std::string& path, const std::string& firstColumn);

// The text of the code span a cell starts with ("`1.0` (nylon)" -> "1.0"), or nullopt if the cell
// does not start with one (prose: not machine-checked).
std::optional<std::string> leadingCode(const std::string& cell);

// Names an expression may use (pi, kMaxDegree, a field's sentinel, ...).
using Symbols = std::map<std::string, double>;

// Evaluates a numeric expression: numbers, `°` after a number (degrees to radians), names from
// `symbols`, unary minus, + - * /, parentheses and one `<<`. Throws std::invalid_argument.
double evaluate(const std::string& expression, const Symbols& symbols);
// "(a, b, c)": the evaluated components. Throws std::invalid_argument.
std::vector<double> evaluateTuple(const std::string& text, const Symbols& symbols);

struct Bound {
  double value = 0.0;
  bool inclusive = false;
};

struct Range {
  std::optional<Bound> lower, upper;
  std::optional<double> excluded;  // "!= c"
  std::vector<double> members;     // "{a, b, c}": only these values
};

// Parses the range grammar above. Throws std::invalid_argument.
Range parseRange(const std::string& text, const Symbols& symbols);

}  // namespace rope::docs
