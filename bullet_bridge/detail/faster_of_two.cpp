// SPDX-License-Identifier: MIT
#include "bullet_bridge/detail/faster_of_two.h"

#include <algorithm>

namespace rope::bullet {

namespace {

template <std::size_t N>
double median(std::array<double, N> values) {
  static_assert(N % 2 == 0, "an even count");
  std::sort(values.begin(), values.end());
  return 0.5 * (values[N / 2 - 1] + values[N / 2]);
}

}  // namespace

void FasterOfTwo::record(double seconds) {
  if (trial_ < kTrialRuns) {
    times_[static_cast<std::size_t>(trial_ % 2)][static_cast<std::size_t>(trial_ / 2)] = seconds;
    if (++trial_ < kTrialRuns) return;
    chosen_ = median(times_[0]) < median(times_[1]) ? 0 : 1;
    chosenLeft_ = kChosenRuns;
    return;
  }
  if (--chosenLeft_ <= 0) trial_ = 0;
}

}  // namespace rope::bullet
