// SPDX-License-Identifier: MIT
#pragma once
// One helper thread that runs one job at a time beside the calling thread (RopeWorld: the rope-rope
// and self-contact detection, which reads only the ropes' state before the substep, while the
// calling thread solves the ropes' body contacts and trial steps; rope_world.cpp).
//
// - The job runs in the caller's floating-point environment (rounding mode, exception traps and
//   flush-to-zero flags, copied at each start): a program that traps FP exceptions traps them in the
//   job too, and the job computes exactly what it would have computed on the caller's thread.
// - Handing a job over costs a few microseconds at most: the helper waits for the next job by
//   spinning for up to kSpinSeconds before it sleeps (wake() ahead of start() wakes it early), and
//   the caller waits for the job's end by spinning before it sleeps. A substep of ropes in contact
//   with each other is some 300 microseconds to a few milliseconds long.
// - A job the helper has not begun when the caller waits for it (the helper asleep, or its core busy
//   with another program) runs on the caller's thread inside wait(), so a busy machine makes a step
//   no slower than running the job there to begin with.
// - If the thread cannot be created (std::system_error), jobs run on the caller's thread inside
//   start(): slower, the same results.
// - An exception the job throws on the helper is rethrown by wait() on the caller's thread (as it
//   would be if wait() ran the job itself). start() and wait() come in pairs from one thread.
// Internal (not installed): rope_world.h holds it through a pointer.

#include <atomic>
#include <condition_variable>
#include <cfenv>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>

namespace rope::bullet {

class SideThread {
 public:
  using Job = void (*)(void* context);
  SideThread() = default;
  ~SideThread();
  SideThread(const SideThread&) = delete;
  SideThread& operator=(const SideThread&) = delete;

  // Wakes the helper if it sleeps, so that it spins for the job start() will hand it soon: its
  // wake-up (tens of microseconds) then passes while the caller prepares the job.
  void wake();
  // Runs job(context) on the helper thread (created at the first call), returning at once.
  void start(Job job, void* context);
  // Returns when the job start() handed over has finished (at once if none is running), after running
  // it here if the helper has not begun it. Throws what the job threw.
  void wait();
  // s: how long either side spins before it sleeps (a 2 m pile's substep hands over every ~0.4 ms).
  static constexpr double kSpinSeconds = 200e-6;

 private:
  void loop();
  std::thread thread_;
  bool threadFailed_ = false;  // the thread could not be created: jobs run inline
  std::mutex mutex_;
  std::condition_variable jobReady_, jobDone_;
  Job job_ = nullptr;
  void* context_ = nullptr;
  std::fenv_t environment_{};
  std::exception_ptr error_;  // what the job threw on the helper, for wait()
  // Jobs handed over, begun (by the helper, or by wait() if the helper had not begun it) and completed.
  std::atomic<std::uint64_t> started_{0}, claimed_{0}, finished_{0};
  bool stop_ = false;   // under mutex_
  bool woken_ = false;  // under mutex_: wake() since the helper last slept
};

}  // namespace rope::bullet
