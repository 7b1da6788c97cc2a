// SPDX-License-Identifier: MIT
#pragma once
// Chooses the faster of two ways of doing the same work, by timing both now and then (RopeWorld:
// a substep's rope-rope contact detection on the side thread or in turn; rope_world.cpp). Which way
// is faster depends on the machine and its load: on an idle second core the side thread shortens the
// 2 m pile's step by a third, and on a core another program keeps busy it lengthens it. The ways
// must give the same results (they do, bit for bit), so the choice changes only the time taken.
//
// Runs come in rounds: kTrialRuns runs alternating the two ways, then kChosenRuns of the one whose
// median time was shorter (ties: way 1). Medians, so that one run stretched by an interrupt or a
// page fault does not decide.
// Internal (not installed): rope_world.h holds it through a pointer.

#include <array>

namespace rope::bullet {

class FasterOfTwo {
 public:
  static constexpr int kTrialRuns = 16;   // 8 of each way
  static constexpr int kChosenRuns = 240;  // then this many of the faster (1 s of 1/240 s substeps)

  // The way (0 or 1) to use for the next run.
  int next() const { return trial_ < kTrialRuns ? trial_ % 2 : chosen_; }
  // The time (s) the run next() named took.
  void record(double seconds);
  // The way the last trial chose (1 before the first trial ends).
  int chosen() const { return chosen_; }

 private:
  std::array<std::array<double, kTrialRuns / 2>, 2> times_{};
  int trial_ = 0;   // runs of the current trial so far; kTrialRuns: running the chosen way
  int chosenLeft_ = 0;
  int chosen_ = 1;
};

}  // namespace rope::bullet
