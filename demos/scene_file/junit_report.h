// SPDX-License-Identifier: MIT
#pragma once
// The checks of a run as a JUnit XML report (`ropesim run --junit FILE.xml`), the format GitHub,
// GitLab and Jenkins display: one <testsuite> for the scene file, one <testcase> per check, a
// <failure> for a check that failed; each case's <system-out> gives the worst value, its unit, the
// bound and the time it happened.

#include <string>
#include <vector>

#include "demos/scene_file/scene_checks.h"

namespace rope::demos {

// suite: the scene file's name; wallSeconds: the run's wall time (the suite's time attribute).
std::string junitReport(const std::string& suite, const std::vector<CheckResult>& results, double wallSeconds);

// Writes it; throws std::runtime_error if the file cannot be written.
void writeJunitReport(const std::string& file, const std::string& suite, const std::vector<CheckResult>& results,
                      double wallSeconds);

}  // namespace rope::demos
