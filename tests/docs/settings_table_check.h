// SPDX-License-Identifier: MIT
#pragma once
// Checks one settings struct against its table in docs/user-guide.md (user_guide_test.cpp lists the
// structs). A StructSpec names the struct as the guide's heading does, lists its fields as member
// pointers (so a renamed or removed field fails to compile) and says how the struct is validated;
// checkSettingsTable() then asserts that
//   * the guide has exactly one table for the struct and it lists exactly these fields, in order;
//   * the struct has exactly as many fields as the spec lists (field_count.h), so a new field fails
//     until it is documented and listed;
//   * each documented default (the cell's leading code span) equals the value-initialised struct's;
//   * each range written as code is the one the validation enforces: a value just outside a bound is
//     rejected with rope::InvalidArgument naming the field, a closed bound itself is not, and a
//     value just inside an open bound is not either.

#include <gtest/gtest.h>

#include <LinearMath/btVector3.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Core>

#include "docs/field_count.h"
#include "docs/guide_tables.h"
#include "rope/common/error.h"

namespace rope::docs {

// The guide's settings tables (read once).
const std::vector<GuideTable>& userGuideTables();
// Names every expression in the guide may use: pi, kMaxDegree, kMaxGaussPoints.
Symbols commonSymbols();

template <class S>
struct Field {
  std::string name;
  std::function<std::string(const std::string&)> checkDefault;  // "" when the documented default matches
  std::function<void(S&, double)> assign;                       // numeric fields (range checks)
  bool integral = false;
  Symbols symbols;                      // commonSymbols() and the field's own sentinels
  std::vector<std::string> enumValues;  // an enum's value names ("kExact"), which its range cell lists
};

template <class S>
struct StructSpec {
  std::string name;    // as the guide's heading names it: "rope::RodSettings"
  std::string prefix;  // how the validation names a field: "settings."
  std::vector<Field<S>> fields;
  std::function<void(const S&)> validate;  // empty: no validation (then no range may be code)
};

// ---- documented default against the struct's default, by field type ----

inline std::string mismatch(const std::string& documented, const std::string& actual) {
  return "the guide says " + documented + ", the struct's default is " + actual;
}

inline std::string compareDefault(double actual, const std::string& text, const Symbols& symbols) {
  const double documented = evaluate(text, symbols);
  const bool same = std::abs(documented - actual) <= 1e-12 * std::max(1.0, std::abs(actual));
  return same ? "" : mismatch(text, formatValue(actual));
}
inline std::string compareDefault(int actual, const std::string& text, const Symbols& symbols) {
  return evaluate(text, symbols) == actual ? "" : mismatch(text, std::to_string(actual));
}
inline std::string compareDefault(bool actual, const std::string& text, const Symbols&) {
  const std::string shown = actual ? "true" : "false";
  return text == shown ? "" : mismatch(text, shown);
}
inline std::string compareDefault(const std::string& actual, const std::string& text, const Symbols&) {
  const std::string shown = "\"" + actual + "\"";
  return text == shown ? "" : mismatch(text, shown);
}
template <class Signature>
std::string compareDefault(const std::function<Signature>& actual, const std::string& text, const Symbols&) {
  const std::string shown = actual ? "a function" : "empty";
  return text == shown ? "" : mismatch(text, shown);
}
// Three components, compared in the vector's own scalar type.
template <class Scalar>
std::string compareComponents(const Scalar* actual, const std::string& text, const Symbols& symbols) {
  const std::vector<double> documented = evaluateTuple(text, symbols);
  std::string shown = "(";
  bool same = documented.size() == 3;
  for (int i = 0; i < 3; ++i) {
    shown += formatValue(static_cast<double>(actual[i])) + (i < 2 ? ", " : ")");
    if (same) {
      const auto value = static_cast<Scalar>(documented[static_cast<std::size_t>(i)]);
      same = std::abs(static_cast<double>(value - actual[i])) <= 1e-12 * std::max(1.0, std::abs(double(actual[i])));
    }
  }
  return same ? "" : mismatch(text, shown);
}
inline std::string compareDefault(const Eigen::Vector3d& actual, const std::string& text, const Symbols& symbols) {
  return compareComponents(actual.data(), text, symbols);
}
inline std::string compareDefault(const Eigen::Vector3f& actual, const std::string& text, const Symbols& symbols) {
  return compareComponents(actual.data(), text, symbols);
}
inline std::string compareDefault(const btVector3& actual, const std::string& text, const Symbols& symbols) {
  return compareComponents(&actual[0], text, symbols);
}

// ---- fields ----

inline Symbols withCommon(Symbols own) {
  Symbols all = commonSymbols();
  all.insert(own.begin(), own.end());
  return all;
}

// A number, vector, string, bool or std::function field; `sentinels` are names its default may use.
template <class S, class T>
Field<S> field(const char* name, T S::*member, Symbols sentinels = {}) {
  Field<S> result;
  result.name = name;
  result.symbols = withCommon(std::move(sentinels));
  const T actual = S{}.*member;
  const Symbols symbols = result.symbols;
  result.checkDefault = [actual, symbols](const std::string& text) { return compareDefault(actual, text, symbols); };
  if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
    result.assign = [member](S& settings, double value) { settings.*member = static_cast<T>(value); };
    result.integral = std::is_integral_v<T>;
  }
  return result;
}

// An enum field, documented by the names of its values ("StretchingQuadrature::kLockingFree").
template <class S, class E>
Field<S> enumField(const char* name, E S::*member, const std::map<E, std::string>& names) {
  Field<S> result;
  result.name = name;
  result.symbols = commonSymbols();
  const E actual = S{}.*member;
  const auto found = names.find(actual);
  const std::string shown = found == names.end() ? "an unnamed value" : found->second;
  result.checkDefault = [shown](const std::string& text) { return text == shown ? "" : mismatch(text, shown); };
  for (const auto& entry : names) result.enumValues.push_back(entry.second.substr(entry.second.rfind(':') + 1));
  return result;
}

// A field that is itself a settings struct with its own table: documented as `{}` (its defaults).
template <class S, class T>
Field<S> nestedField(const char* name, T S::*) {
  Field<S> result;
  result.name = name;
  result.symbols = commonSymbols();
  result.checkDefault = [](const std::string& text) { return text == "{}" ? "" : mismatch(text, "{}"); };
  return result;
}

// ---- the checks ----

// The parameter an InvalidArgument from validate names for the default struct with `field` set to
// `value`, or "" if validate accepts it (other exceptions, such as a missing ffmpeg, count as
// accepted: the settings themselves passed).
template <class S>
std::string rejectedParameter(const StructSpec<S>& spec, const Field<S>& field, double value) {
  S settings{};
  field.assign(settings, value);
  try {
    spec.validate(settings);
  } catch (const InvalidArgument& error) {
    return error.parameter();
  } catch (const std::exception&) {
  }
  return "";
}

// An enum's range cell names every value of the enum, each as code.
template <class S>
void checkEnumRange(const Field<S>& field, const std::string& cell) {
  std::vector<std::string> documented;
  for (std::size_t open = cell.find('`'); open != std::string::npos; open = cell.find('`', open + 1)) {
    const std::size_t close = cell.find('`', open + 1);
    if (close == std::string::npos) break;
    documented.push_back(cell.substr(open + 1, close - open - 1));
    open = close;
  }
  std::vector<std::string> values = field.enumValues;
  std::sort(documented.begin(), documented.end());
  std::sort(values.begin(), values.end());
  EXPECT_EQ(documented, values) << "the values listed in the range cell: " << cell;
}

template <class S>
void checkRange(const StructSpec<S>& spec, const Field<S>& field, const std::string& code) {
  ASSERT_TRUE(field.assign) << "a range written as code on a field that is not a number";
  ASSERT_TRUE(spec.validate) << spec.name << " has no validation in the test, so its ranges cannot be code";
  Range range;
  try {
    range = parseRange(code, field.symbols);
  } catch (const std::invalid_argument& error) {
    FAIL() << "range " << error.what();
  }
  const std::string parameter = spec.prefix + field.name;
  const auto rejected = [&](double value) {
    EXPECT_EQ(rejectedParameter(spec, field, value), parameter) << "value " << formatValue(value) << ", range " << code;
  };
  const auto accepted = [&](double value) {
    EXPECT_NE(rejectedParameter(spec, field, value), parameter) << "value " << formatValue(value) << ", range " << code;
  };
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  // Just outside a closed bound, and just inside an open one (a visible step for doubles, so that a
  // validation that rejects a little more than the bound is caught as well).
  const auto beyond = [&](double bound, double direction) {
    return field.integral ? bound + direction : std::nextafter(bound, direction * kInfinity);
  };
  const auto within = [&](double bound, double direction) {
    return field.integral ? bound + direction : bound + direction * 1e-6 * std::max(1.0, std::abs(bound));
  };
  for (const auto& [bound, direction] : {std::pair{range.lower, -1.0}, std::pair{range.upper, 1.0}}) {
    if (!bound) continue;
    if (bound->inclusive) {
      accepted(bound->value);
      rejected(beyond(bound->value, direction));
    } else {
      rejected(bound->value);
      accepted(within(bound->value, -direction));
    }
  }
  if (range.excluded) {
    rejected(*range.excluded);
    accepted(*range.excluded + 1.0);
  }
  if (!range.members.empty()) {
    ASSERT_TRUE(field.integral) << "a set of values is for whole numbers";
    const auto [low, high] = std::minmax_element(range.members.begin(), range.members.end());
    // Every other whole number from below the smallest to twice the largest.
    for (double value = *low - 1.0; value <= 2.0 * *high + 1.0; value += 1.0) {
      const bool member = std::find(range.members.begin(), range.members.end(), value) != range.members.end();
      if (member) accepted(value);
      else rejected(value);
    }
  }
}

template <class S>
void checkRow(const StructSpec<S>& spec, const Field<S>& field, const GuideRow& row) {
  SCOPED_TRACE("docs/user-guide.md:" + std::to_string(row.line) + ": " + spec.name + "::" + field.name);
  const auto defaultCode = leadingCode(row.defaultValue);
  EXPECT_TRUE(defaultCode.has_value()) << "the default cell must start with the value as code: " << row.defaultValue;
  if (defaultCode) {
    try {
      EXPECT_EQ(field.checkDefault(*defaultCode), "");
    } catch (const std::invalid_argument& error) {
      ADD_FAILURE() << "default " << error.what();
    }
  }
  if (!field.enumValues.empty()) {
    checkEnumRange(field, row.range);
  } else if (const auto rangeCode = leadingCode(row.range)) {
    checkRange(spec, field, *rangeCode);
  }
}

template <class S>
void checkSettingsTable(const StructSpec<S>& spec) {
  std::vector<const GuideTable*> tables;
  for (const GuideTable& table : userGuideTables()) {
    if (table.owner == spec.name) tables.push_back(&table);
  }
  ASSERT_EQ(tables.size(), 1u) << "docs/user-guide.md needs exactly one settings table under a heading naming `"
                               << spec.name << "`";
  EXPECT_EQ(spec.fields.size(), fieldCount<S>())
      << spec.name << " has " << fieldCount<S>() << " fields and the test lists " << spec.fields.size()
      << ": document every field in docs/user-guide.md and list it in tests/docs/user_guide_test.cpp";
  std::vector<std::string> documented, listed;
  for (const GuideRow& row : tables.front()->rows) documented.push_back(leadingCode(row.field).value_or(row.field));
  for (const Field<S>& field : spec.fields) listed.push_back(field.name);
  EXPECT_EQ(documented, listed) << "the fields of " << spec.name << "'s table (line " << tables.front()->line
                                << "), in the struct's order";
  for (const GuideRow& row : tables.front()->rows) {
    const auto found = std::find_if(spec.fields.begin(), spec.fields.end(),
                                    [&](const Field<S>& field) { return field.name == leadingCode(row.field); });
    if (found != spec.fields.end()) checkRow(spec, *found, row);
  }
}

}  // namespace rope::docs
