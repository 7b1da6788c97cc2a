// SPDX-License-Identifier: MIT
#include "rope/common/error.h"

#include <cmath>
#include <cstdio>

namespace rope {

InvalidArgument::InvalidArgument(const std::string& parameter, const std::string& value,
                                 const std::string& reason)
    : std::invalid_argument(parameter + " = " + value + ": " + reason), parameter_(parameter) {}

std::string formatValue(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

void requireFinite(const std::string& parameter, double value) {
  if (!std::isfinite(value)) throw InvalidArgument(parameter, formatValue(value), "must be finite");
}

void requirePositive(const std::string& parameter, double value) {
  requireFinite(parameter, value);
  if (!(value > 0.0)) throw InvalidArgument(parameter, formatValue(value), "must be > 0");
}

void requireNonNegative(const std::string& parameter, double value) {
  requireFinite(parameter, value);
  if (value < 0.0) throw InvalidArgument(parameter, formatValue(value), "must be >= 0");
}

void requireFinite(const char* parameter, double value) {
  if (!std::isfinite(value)) requireFinite(std::string(parameter), value);
}

void requirePositive(const char* parameter, double value) {
  if (!(std::isfinite(value) && value > 0.0)) requirePositive(std::string(parameter), value);
}

void requireNonNegative(const char* parameter, double value) {
  if (!(std::isfinite(value) && value >= 0.0)) requireNonNegative(std::string(parameter), value);
}

}  // namespace rope
