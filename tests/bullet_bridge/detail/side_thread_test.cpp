// SPDX-License-Identifier: MIT
#include "bullet_bridge/detail/side_thread.h"

#include <gtest/gtest.h>

#include <cfenv>
#include <chrono>
#include <thread>

namespace rope::bullet {
namespace {

struct Record {
  int runs = 0;
  std::thread::id thread;
  int rounding = -1;
  int traps = -1;
};

void recordJob(void* context) {
  Record& record = *static_cast<Record*>(context);
  ++record.runs;
  record.thread = std::this_thread::get_id();
  record.rounding = std::fegetround();
  record.traps = fegetexcept();
}

TEST(SideThread, RunsEachJobOnceOnAnotherThreadAndWaitReturnsAfterIt) {
  SideThread side;
  Record record;
  for (int k = 1; k <= 2000; ++k) {
    side.start(recordJob, &record);
    side.wait();
    ASSERT_EQ(record.runs, k);  // not atomic: wait() orders the job's writes before this read
  }
  EXPECT_NE(record.thread, std::this_thread::get_id());
  side.wait();  // no job running: returns at once
  EXPECT_EQ(record.runs, 2000);
}

TEST(SideThread, WakesFromSleepForTheNextJob) {
  SideThread side;
  Record record;
  for (int k = 1; k <= 5; ++k) {
    // Longer than both sides spin, so the helper is asleep when the job comes.
    std::this_thread::sleep_for(std::chrono::duration<double>(4.0 * SideThread::kSpinSeconds));
    side.start(recordJob, &record);
    side.wait();
    EXPECT_EQ(record.runs, k);
  }
}

TEST(SideThread, JobRunsInTheCallersFloatingPointEnvironment) {
  std::fenv_t saved;
  std::fegetenv(&saved);
  const int rounding = std::fegetround(), traps = fegetexcept();  // the test program's (it traps)
  SideThread side;
  Record record;
  side.start(recordJob, &record);
  side.wait();
  EXPECT_EQ(record.rounding, rounding);
  EXPECT_EQ(record.traps, traps);
  std::fesetround(FE_UPWARD);
  fedisableexcept(FE_ALL_EXCEPT);
  feenableexcept(FE_DIVBYZERO);
  side.start(recordJob, &record);
  side.wait();
  std::fesetenv(&saved);
  EXPECT_EQ(record.rounding, FE_UPWARD);
  EXPECT_EQ(record.traps, FE_DIVBYZERO);
  side.start(recordJob, &record);  // and back
  side.wait();
  EXPECT_EQ(record.rounding, rounding);
  EXPECT_EQ(record.traps, traps);
}

TEST(SideThread, DestroyedWithoutAJobOrAfterOne) {
  { SideThread unused; }
  Record record;
  {
    SideThread side;
    side.start(recordJob, &record);
    side.wait();
  }
  EXPECT_EQ(record.runs, 1);
}

}  // namespace
}  // namespace rope::bullet
