// SPDX-License-Identifier: MIT
#include "bullet_bridge/detail/side_thread.h"

#include <chrono>
#include <system_error>
#include <utility>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace rope::bullet {

namespace {

// One spin of a wait: tells the core that this is a spin loop (x86: pause), so the sibling
// hyperthread gets the pipeline and the loop's exit costs no memory-order mis-speculation.
inline void relax() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#else
  std::this_thread::yield();
#endif
}

// Spins until done() or kSpinSeconds have passed; true if done() became true.
template <class Done>
bool spinUntil(const Done& done) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                   std::chrono::duration<double>(SideThread::kSpinSeconds));
  for (;;) {
    for (int i = 0; i < 64; ++i) {
      if (done()) return true;
      relax();
    }
    if (Clock::now() >= end) return done();
  }
}

}  // namespace

SideThread::~SideThread() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  jobReady_.notify_one();
  thread_.join();
}

void SideThread::wake() {
  if (!thread_.joinable()) return;  // start() creates it
  {
    std::lock_guard<std::mutex> lock(mutex_);
    woken_ = true;
  }
  jobReady_.notify_one();
}

void SideThread::start(Job job, void* context) {
  if (!thread_.joinable() && !threadFailed_) {
    try {
      thread_ = std::thread([this] { loop(); });
    } catch (const std::system_error&) {
      threadFailed_ = true;
    }
  }
  if (threadFailed_) {
    job(context);
    return;
  }
  job_ = job;
  context_ = context;
  std::fegetenv(&environment_);
  {
    // Under the mutex, so that a helper about to sleep either sees the new count or is woken.
    std::lock_guard<std::mutex> lock(mutex_);
    started_.store(started_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
  }
  jobReady_.notify_one();
}

void SideThread::wait() {
  const std::uint64_t target = started_.load(std::memory_order_relaxed);
  const auto done = [&] { return finished_.load(std::memory_order_acquire) == target; };
  if (!done()) {
    // A job the helper has not begun yet (asleep, or not given a core) runs here: never slower than
    // running it here in the first place.
    std::uint64_t unclaimed = target - 1;
    if (claimed_.compare_exchange_strong(unclaimed, target, std::memory_order_acq_rel)) {
      try {
        job_(context_);
      } catch (...) {
        finished_.store(target, std::memory_order_release);  // ended, if not well
        throw;
      }
      finished_.store(target, std::memory_order_release);
      return;
    }
    if (!spinUntil(done)) {
      std::unique_lock<std::mutex> lock(mutex_);
      jobDone_.wait(lock, done);
    }
  }
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

void SideThread::loop() {
  std::uint64_t seen = 0;
  for (;;) {
    const auto ready = [&] { return started_.load(std::memory_order_acquire) != seen; };
    if (!spinUntil(ready)) {
      std::unique_lock<std::mutex> lock(mutex_);
      woken_ = false;
      jobReady_.wait(lock, [&] { return stop_ || woken_ || ready(); });
      if (stop_ && !ready()) return;
      if (!ready()) continue;  // woken ahead of a job: spin for it
    }
    seen = started_.load(std::memory_order_acquire);
    std::uint64_t unclaimed = seen - 1;
    if (!claimed_.compare_exchange_strong(unclaimed, seen, std::memory_order_acq_rel)) continue;  // wait() ran it
    std::fesetenv(&environment_);
    try {
      job_(context_);
    } catch (...) {
      error_ = std::current_exception();
    }
    {
      // Under the mutex, so that a caller about to sleep either sees the count or is woken.
      std::lock_guard<std::mutex> lock(mutex_);
      finished_.store(seen, std::memory_order_release);
    }
    jobDone_.notify_one();
  }
}

}  // namespace rope::bullet
