// SPDX-License-Identifier: MIT
#include "support/fp_exceptions.h"

#include <cfenv>

namespace rope::test {

namespace {
constexpr int kTrapped = FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW;
}

void enableFloatingPointTraps() {
  std::feclearexcept(FE_ALL_EXCEPT);
  feenableexcept(kTrapped);
}

void disableFloatingPointTraps() { fedisableexcept(FE_ALL_EXCEPT); }

ScopedNoFloatingPointTraps::ScopedNoFloatingPointTraps() : saved_(fegetexcept()) {
  disableFloatingPointTraps();
}

ScopedNoFloatingPointTraps::~ScopedNoFloatingPointTraps() {
  std::feclearexcept(FE_ALL_EXCEPT);
  feenableexcept(saved_);
}

}  // namespace rope::test
