// SPDX-License-Identifier: MIT
// libFuzzer entry point of one of the three fuzzers of fuzz.h, chosen when compiled
// (SPLINEROPE_FUZZ_ENTRY: fuzzSplineBytes, fuzzSettingsBytes or fuzzSceneBytes). Built only by the
// `fuzz` preset (clang, -fsanitize=fuzzer,address,undefined); CONTRIBUTING.md says how to run them.
// fuzz.cpp reports a broken invariant with GoogleTest's EXPECT_*: outside a running test GoogleTest
// still prints it, and the listener below then aborts, so libFuzzer keeps the input as a crash.
// Floating-point traps are on for each input (as in every test binary), off in libFuzzer's own code.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "reliability/fuzz.h"
#include "support/fp_exceptions.h"

namespace {

class AbortOnFailure : public ::testing::EmptyTestEventListener {
  void OnTestPartResult(const ::testing::TestPartResult& result) override {
    if (!result.failed()) return;
    std::fprintf(stderr, "%s:%d: invariant broken\n%s\n", result.file_name() != nullptr ? result.file_name() : "?",
                 result.line_number(), result.message());
    std::abort();
  }
};

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ::testing::UnitTest::GetInstance()->listeners().Append(new AbortOnFailure);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rope::test::enableFloatingPointTraps();
  rope::test::SPLINEROPE_FUZZ_ENTRY(data, size);
  rope::test::disableFloatingPointTraps();
  return 0;
}
