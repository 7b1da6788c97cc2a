// SPDX-License-Identifier: MIT
#pragma once
// Errors raised by SplineRope. Bad user input throws InvalidArgument whose message names the
// offending parameter and its value; the object it was called on is left exactly as it was.
// Numerical failure (NaN, failed factorisation) is reported with NumericalFailure or an error result,
// never propagated silently into the state.

#include <stdexcept>
#include <string>

namespace rope {

class InvalidArgument : public std::invalid_argument {
 public:
  // parameter: the name the user knows (e.g. "knots[3]", "s", "settings.radius").
  // value: the offending value as text; reason: what was expected ("must be > 0").
  InvalidArgument(const std::string& parameter, const std::string& value, const std::string& reason);
  const std::string& parameter() const { return parameter_; }

 private:
  std::string parameter_;
};

class NumericalFailure : public std::runtime_error {
 public:
  explicit NumericalFailure(const std::string& what) : std::runtime_error(what) {}
};

// Formats a double for error messages with full round-trip precision ("nan", "inf" included).
std::string formatValue(double value);

// Validation helpers. They test finiteness first: an ordered comparison against NaN raises the
// floating-point "invalid" exception, which the tests trap.
void requireFinite(const std::string& parameter, double value);
void requirePositive(const std::string& parameter, double value);     // finite and > 0
void requireNonNegative(const std::string& parameter, double value);  // finite and >= 0
// The same for a name given as a C string (a literal): the std::string is built only for the error,
// so a check on a per-step path allocates nothing (names past the small-string buffer would).
void requireFinite(const char* parameter, double value);
void requirePositive(const char* parameter, double value);
void requireNonNegative(const char* parameter, double value);

}  // namespace rope
