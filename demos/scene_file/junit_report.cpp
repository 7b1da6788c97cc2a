// SPDX-License-Identifier: MIT
#include "demos/scene_file/junit_report.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rope::demos {

namespace {

std::string escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

}  // namespace

std::string junitReport(const std::string& suite, const std::vector<CheckResult>& results, double wallSeconds) {
  int failures = 0;
  for (const CheckResult& result : results) failures += result.passed ? 0 : 1;
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<testsuites name=\"ropesim\" tests=\"" << results.size() << "\" failures=\"" << failures
      << "\" errors=\"0\" time=\"" << number(wallSeconds) << "\">\n"
      << "  <testsuite name=\"" << escape(suite) << "\" tests=\"" << results.size() << "\" failures=\"" << failures
      << "\" errors=\"0\" skipped=\"0\" time=\"" << number(wallSeconds) << "\">\n";
  for (const CheckResult& result : results) {
    xml << "    <testcase name=\"" << escape(result.name) << "\" classname=\"" << escape(suite) << "." << result.type
        << "\" time=\"0\">\n";
    if (!result.passed) {
      xml << "      <failure type=\"" << result.type << "\" message=\"" << escape(result.message) << "\">"
          << escape(result.message) << "</failure>\n";
    }
    xml << "      <system-out>type=" << result.type << " worst=" << number(result.worst) << " unit=" << escape(result.unit)
        << " bound=\"" << escape(result.bound) << "\" time=" << number(result.worstTime) << " samples=" << result.samples
        << " first_failure=" << number(result.firstFailureTime)
        << "</system-out>\n"
        << "    </testcase>\n";
  }
  xml << "  </testsuite>\n</testsuites>\n";
  return xml.str();
}

void writeJunitReport(const std::string& file, const std::string& suite, const std::vector<CheckResult>& results,
                      double wallSeconds) {
  std::ofstream stream(file);
  stream << junitReport(suite, results, wallSeconds);
  if (!stream) throw std::runtime_error("cannot write the JUnit report to '" + file + "'");
}

}  // namespace rope::demos
