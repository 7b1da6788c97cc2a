// SPDX-License-Identifier: MIT
#pragma once
// Progress output for long runs: a redrawn bar with an ETA on a terminal, and a quiet line every
// 10% elsewhere (CI logs), on standard error so that standard output stays clean.

#include <chrono>
#include <string>

namespace rope::demos {

class Progress {
 public:
  // total: number of units (frames); label: what is being done.
  Progress(long total, std::string label, bool quiet);
  void update(long done);
  void finish();

 private:
  long total_;
  std::string label_;
  bool quiet_;
  bool terminal_;
  int lastDecile_ = -1;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace rope::demos
