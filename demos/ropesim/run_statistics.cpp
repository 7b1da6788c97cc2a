// SPDX-License-Identifier: MIT
#include "demos/ropesim/run_statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace rope::demos {

namespace {

std::string number(double value) {
  if (!std::isfinite(value)) return "null";  // JSON has no NaN or infinity
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", value);
  return buffer;
}

std::string optionalNumber(const std::optional<double>& value) {
  return value ? number(*value) : "null";
}

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\u%04x", c);
      out += escape;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string array(const std::vector<double>& values) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0) out += ',';
    out += number(values[i]);
  }
  return out + "]";
}

void keepMax(std::optional<double>& current, const std::optional<double>& value) {
  if (value && (!current || *value > *current)) current = value;
}

}  // namespace

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double position = q * static_cast<double>(values.size() - 1);
  const std::size_t below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, values.size() - 1);
  const double fraction = position - static_cast<double>(below);
  return values[below] + fraction * (values[above] - values[below]);
}

void RunStatistics::addStep(const StepMeasurements& measurements, double wallMicroseconds,
                            double simulatedTime) {
  if (steps_ == 0) {
    minControlPoints_ = maxControlPoints_ = measurements.controlPoints;
  }
  ++steps_;
  simulatedSeconds_ = simulatedTime;
  stepMicroseconds_.push_back(wallMicroseconds);
  minControlPoints_ = std::min(minControlPoints_, measurements.controlPoints);
  maxControlPoints_ = std::max(maxControlPoints_, measurements.controlPoints);
  finalControlPoints_ = measurements.controlPoints;
  insertions_ += measurements.insertions;
  removals_ += measurements.removals;
  maxStrain_ = std::max(maxStrain_, measurements.maxStrain);
  keepMax(maxPenetration_, measurements.maxPenetration);
  keepMax(maxSelfOverlap_, measurements.maxSelfOverlap);
}

void RunStatistics::addFrame(double time, const StepMeasurements& latest) {
  frameTimes_.push_back(time);
  frameControlPoints_.push_back(latest.controlPoints);
  frameMaxStrain_.push_back(latest.maxStrain);
  // Every series has one entry per frame; frames that did not report it get NaN (null in JSON).
  const std::size_t frames = frameTimes_.size();
  for (const auto& [name, value] : latest.series) {
    auto series = std::find_if(frameSeries_.begin(), frameSeries_.end(),
                               [&](const auto& entry) { return entry.first == name; });
    if (series == frameSeries_.end()) {
      frameSeries_.push_back({name, {}});
      series = frameSeries_.end() - 1;
    }
    series->second.resize(frames - 1, std::numeric_limits<double>::quiet_NaN());
    series->second.push_back(value);
  }
  for (auto& entry : frameSeries_) entry.second.resize(frames, std::numeric_limits<double>::quiet_NaN());
}

double RunStatistics::stepTimeMedian() const { return quantile(stepMicroseconds_, 0.5); }
double RunStatistics::stepTimeP95() const { return quantile(stepMicroseconds_, 0.95); }

std::string RunStatistics::toJson() const {
  std::ostringstream json;
  json << "{\n"
       << "  \"scene\": " << quoted(scene_) << ",\n"
       << "  \"simulated_seconds\": " << number(simulatedSeconds_) << ",\n"
       << "  \"steps\": " << steps_ << ",\n"
       << "  \"step_time_us\": {\"median\": " << number(stepTimeMedian())
       << ", \"p95\": " << number(stepTimeP95()) << "},\n"
       << "  \"control_points\": {\"min\": " << minControlPoints_ << ", \"max\": " << maxControlPoints_
       << ", \"final\": " << finalControlPoints_ << "},\n"
       << "  \"insertions\": " << insertions_ << ",\n"
       << "  \"removals\": " << removals_ << ",\n"
       << "  \"max_penetration_m\": " << optionalNumber(maxPenetration_) << ",\n"
       << "  \"max_self_overlap_m\": " << optionalNumber(maxSelfOverlap_) << ",\n"
       << "  \"max_strain\": " << number(maxStrain_) << ",\n"
       << "  \"render_fps\": " << optionalNumber(renderFps_) << ",\n"
       // Per-frame arrays sit in their own object: "control_points" and "max_strain" above are the
       // run's summary, these are the same quantities frame by frame.
       << "  \"frames\": {\n"
       << "    \"t\": " << array(frameTimes_) << ",\n"
       << "    \"control_points\": " << array(frameControlPoints_) << ",\n"
       << "    \"max_strain\": " << array(frameMaxStrain_);
  for (const auto& [name, values] : frameSeries_) {
    json << ",\n    " << quoted(name) << ": " << array(values);
  }
  json << "\n  }\n}\n";
  return json.str();
}

}  // namespace rope::demos
