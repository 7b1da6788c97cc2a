// SPDX-License-Identifier: MIT
#pragma once
// Floating-point exception trapping for tests: an invalid operation (NaN from 0/0, sqrt(-1), an
// ordered comparison with NaN), a division by zero or an overflow stops the test with SIGFPE at the
// faulting instruction instead of letting a NaN travel on.

namespace rope::test {

void enableFloatingPointTraps();
void disableFloatingPointTraps();

// Disables the traps for a scope, for third-party code that computes with NaN/inf on purpose
// (e.g. Mesa's llvmpipe) — never for SplineRope's own code.
class ScopedNoFloatingPointTraps {
 public:
  ScopedNoFloatingPointTraps();
  ~ScopedNoFloatingPointTraps();
  ScopedNoFloatingPointTraps(const ScopedNoFloatingPointTraps&) = delete;
  ScopedNoFloatingPointTraps& operator=(const ScopedNoFloatingPointTraps&) = delete;

 private:
  int saved_;
};

}  // namespace rope::test
