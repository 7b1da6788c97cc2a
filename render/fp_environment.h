// SPDX-License-Identifier: MIT
#pragma once
// Mesa's llvmpipe computes with NaN and infinity on purpose (clipping, derivatives, culling). A
// program that traps floating-point exceptions (as SplineRope's tests do) would die inside Mesa, so
// every GL call in this library runs inside this guard: it saves the caller's environment, masks
// all exceptions, and restores environment and flags when the scope ends. Mesa's worker threads
// inherit the masked environment because the context is created inside the guard too.

#include <cfenv>

namespace rope::render {

class FloatingPointGuard {
 public:
  FloatingPointGuard() { feholdexcept(&saved_); }
  ~FloatingPointGuard() { fesetenv(&saved_); }
  FloatingPointGuard(const FloatingPointGuard&) = delete;
  FloatingPointGuard& operator=(const FloatingPointGuard&) = delete;

 private:
  std::fenv_t saved_;
};

}  // namespace rope::render
