// SPDX-License-Identifier: MIT
#include "bullet_bridge/detail/side_thread.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cfenv>
#include <chrono>
#include <stdexcept>
#include <thread>

namespace rope::bullet {
namespace {

struct Record {
  int runs = 0;
  std::thread::id thread;
  int rounding = -1;
  int traps = -1;
  std::atomic<int> published{0};  // runs, stored last: the caller can watch it without wait()
};

void recordJob(void* context) {
  Record& record = *static_cast<Record*>(context);
  ++record.runs;
  record.thread = std::this_thread::get_id();
  record.rounding = std::fegetround();
  record.traps = fegetexcept();
  record.published.store(record.runs, std::memory_order_release);
}

// Starts the job and lets the helper run it: the caller watches for its end before wait(), which
// would otherwise run a job the helper has not begun itself.
void runOnHelper(SideThread& side, Record& record) {
  const int before = record.published.load(std::memory_order_acquire);
  side.start(recordJob, &record);
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (record.published.load(std::memory_order_acquire) == before && std::chrono::steady_clock::now() < end) {
    std::this_thread::yield();
  }
  side.wait();
}

TEST(SideThread, HelperRunsTheJobOnItsOwnThread) {
  SideThread side;
  Record record;
  for (int k = 1; k <= 3; ++k) {
    runOnHelper(side, record);
    EXPECT_EQ(record.runs, k);
    EXPECT_NE(record.thread, std::this_thread::get_id());
  }
}

TEST(SideThread, RunsEachJobOnceAndWaitReturnsAfterIt) {
  SideThread side;
  Record record;
  for (int k = 1; k <= 2000; ++k) {
    side.start(recordJob, &record);
    side.wait();  // the job ran on the helper, or here if the helper had not begun it
    ASSERT_EQ(record.runs, k);  // not atomic: wait() orders the job's writes before this read
  }
  side.wait();  // no job running: returns at once
  EXPECT_EQ(record.runs, 2000);
}

TEST(SideThread, RunsEachJobOnceWhetherTheHelperSleptOrWasWoken) {
  SideThread side;
  Record record;
  for (int k = 1; k <= 20; ++k) {
    // Longer than both sides spin, so the helper is asleep when the job comes: wait() right away
    // mostly runs it itself; after wake() the helper mostly does. Either way exactly once.
    std::this_thread::sleep_for(std::chrono::duration<double>(4.0 * SideThread::kSpinSeconds));
    if (k % 2 == 0) {
      side.wake();
      std::this_thread::sleep_for(std::chrono::duration<double>(0.25 * SideThread::kSpinSeconds));
    }
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
  runOnHelper(side, record);
  EXPECT_EQ(record.rounding, rounding);
  EXPECT_EQ(record.traps, traps);
  std::fesetround(FE_UPWARD);
  fedisableexcept(FE_ALL_EXCEPT);
  feenableexcept(FE_DIVBYZERO);
  runOnHelper(side, record);
  std::fesetenv(&saved);
  EXPECT_NE(record.thread, std::this_thread::get_id());
  EXPECT_EQ(record.rounding, FE_UPWARD);
  EXPECT_EQ(record.traps, FE_DIVBYZERO);
  runOnHelper(side, record);  // and back
  EXPECT_EQ(record.rounding, rounding);
  EXPECT_EQ(record.traps, traps);
}

void throwingJob(void* context) {
  recordJob(context);
  throw std::runtime_error("thrown by the job");
}

TEST(SideThread, WaitRethrowsWhatTheJobThrewOnEitherThread) {
  SideThread side;
  Record record;
  // On the helper (the caller waits for its end before wait()) ...
  const int before = record.published.load(std::memory_order_acquire);
  side.start(throwingJob, &record);
  while (record.published.load(std::memory_order_acquire) == before) std::this_thread::yield();
  EXPECT_THROW(side.wait(), std::runtime_error);
  side.wait();  // once: the job has ended
  // ... and in wait() itself, mostly (the helper asleep), or on the helper.
  std::this_thread::sleep_for(std::chrono::duration<double>(4.0 * SideThread::kSpinSeconds));
  side.start(throwingJob, &record);
  EXPECT_THROW(side.wait(), std::runtime_error);
  side.wait();
  // The thread goes on with the next job.
  runOnHelper(side, record);
  EXPECT_EQ(record.runs, 3);
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
