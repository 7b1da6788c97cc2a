// SPDX-License-Identifier: MIT
#include "bullet_bridge/detail/faster_of_two.h"

#include <gtest/gtest.h>

namespace rope::bullet {
namespace {

// Runs `runs` runs in which way 0 takes t0 seconds and way 1 t1; counts the runs of way 1.
int runWays(FasterOfTwo& chooser, int runs, double t0, double t1) {
  int ones = 0;
  for (int k = 0; k < runs; ++k) {
    const int way = chooser.next();
    ones += way;
    chooser.record(way == 0 ? t0 : t1);
  }
  return ones;
}

TEST(FasterOfTwo, TriesBothThenRunsTheFasterUntilTheNextTrial) {
  FasterOfTwo chooser;
  const int trial = FasterOfTwo::kTrialRuns, chosen = FasterOfTwo::kChosenRuns;
  // A trial alternates the ways, starting with 0.
  for (int k = 0; k < trial; ++k) {
    EXPECT_EQ(chooser.next(), k % 2);
    chooser.record(k % 2 == 0 ? 2e-3 : 1e-3);  // way 1 is faster
  }
  EXPECT_EQ(chooser.chosen(), 1);
  EXPECT_EQ(runWays(chooser, chosen, 2e-3, 1e-3), chosen);  // all way 1
  // The machine changes: way 0 is now faster; the next trial sees it.
  EXPECT_EQ(runWays(chooser, trial, 1e-3, 3e-3), trial / 2);
  EXPECT_EQ(chooser.chosen(), 0);
  EXPECT_EQ(runWays(chooser, chosen, 1e-3, 3e-3), 0);  // all way 0
  EXPECT_EQ(chooser.next(), 0);                          // the next trial begins
}

TEST(FasterOfTwo, OneSlowRunDoesNotDecide) {
  FasterOfTwo chooser;
  for (int k = 0; k < FasterOfTwo::kTrialRuns; ++k) {
    const int way = chooser.next();
    // Way 1 is faster in every run but one, stretched tenfold (an interrupt, a page fault).
    double seconds = way == 0 ? 2e-3 : 1e-3;
    if (k == 1) seconds = 1e-2;
    chooser.record(seconds);
  }
  EXPECT_EQ(chooser.chosen(), 1);
}

}  // namespace
}  // namespace rope::bullet
