// SPDX-License-Identifier: MIT
#include "demos/ropesim/progress.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace rope::demos {

namespace {
bool isInteractive() {
  // CI systems set CI=true; their logs want lines, not carriage returns.
  const char* ci = std::getenv("CI");
  if (ci != nullptr && std::strcmp(ci, "") != 0 && std::strcmp(ci, "false") != 0) return false;
  return isatty(STDERR_FILENO) == 1;
}
}  // namespace

Progress::Progress(long total, std::string label, bool quiet)
    : total_(total > 0 ? total : 1), label_(std::move(label)), quiet_(quiet),
      terminal_(isInteractive()), start_(std::chrono::steady_clock::now()) {}

void Progress::update(long done) {
  if (quiet_) return;
  const double fraction = static_cast<double>(done) / static_cast<double>(total_);
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta = done > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  if (terminal_) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    std::fprintf(stderr, "\r%s [%.*s%*s] %3d%% %ld/%ld  ETA %4.0f s ", label_.c_str(), filled,
                 "##############################", kWidth - filled, "", static_cast<int>(100 * fraction),
                 done, total_, eta);
    std::fflush(stderr);
  } else {
    const int decile = static_cast<int>(10 * fraction);
    if (decile != lastDecile_) {
      lastDecile_ = decile;
      std::fprintf(stderr, "%s: %d%% (%ld/%ld), %.1f s elapsed\n", label_.c_str(), 10 * decile, done,
                   total_, elapsed);
    }
  }
}

void Progress::finish() {
  if (quiet_) return;
  update(total_);
  if (terminal_) std::fputc('\n', stderr);
}

}  // namespace rope::demos
