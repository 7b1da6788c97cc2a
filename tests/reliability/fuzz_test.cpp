// SPDX-License-Identifier: MIT
// Deterministic fuzzing (issue 17): random sequences of operations and random, often bad, inputs from
// a fixed seed, checked against invariants after every operation. The floating-point traps stay on,
// so a NaN or an overflow in the library stops the test where it happens.
//   - spline operations on a rod (insert, remove, cut, evaluate, step): an insertion never moves the
//     curve (1e-12 relative) nor changes mass or momentum (1e-12 relative); a removal moves the curve
//     by no more than the bound it reports; a cut reproduces the curve on both pieces; a refused call
//     (InvalidArgument) changes nothing;
//   - settings validation: random field values (NaN, inf, zero, negative, huge, tiny, ordinary) are
//     either refused with InvalidArgument naming a "settings." field, or give a rope whose steps never
//     throw and whose state stays finite (a failed step is reported and keeps the state);
//   - a small Bullet scene driven by a random script (pins, cuts, forces, bodies moved, added and
//     deleted, attachments, kinematic rope targets, bad time steps): nothing escapes a step, every
//     rope's state stays finite, a refused call changes nothing.
// Each test runs a fixed number of rounds (kRounds); SPLINEROPE_FUZZ_ROUNDS multiplies them (the
// soak label's reliability_soak_test runs them 20 times longer with other seeds).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "bullet_bridge/kinematic_rope.h"
#include "bullet_bridge/rope_world.h"
#include "reliability/fuzz.h"
#include "reliability/reliability_support.h"
#include "rope/common/error.h"

namespace rope::test {
namespace {

int rounds(int base) {
  const char* scale = std::getenv("SPLINEROPE_FUZZ_ROUNDS");
  return scale != nullptr ? base * std::max(1, std::atoi(scale)) : base;
}

TEST(Fuzz, SplineOperationsKeepTheirInvariants) {
  const FuzzTotals totals = fuzzSplineOperations(0x5eed0001, rounds(600));
  std::printf("spline fuzz: %ld operations (%ld insertions, %ld removals, %ld cuts, %ld refused)\n", totals.operations,
              totals.insertions, totals.removals, totals.cuts, totals.refused);
  EXPECT_GT(totals.insertions, 1000);
  EXPECT_GT(totals.removals, 10);
  EXPECT_GT(totals.cuts, 10);
  EXPECT_GT(totals.refused, 100);
}

TEST(Fuzz, SettingsAreRefusedOrGiveARopeThatSteps) {
  const FuzzTotals totals = fuzzSettings(0x5eed0002, rounds(4000));
  std::printf("settings fuzz: %ld settings tried, %ld refused, %ld accepted and stepped (%ld steps failed and were reported)\n",
              totals.operations, totals.refused, totals.operations - totals.refused, totals.failedSteps);
  EXPECT_GT(totals.refused, 100);
  EXPECT_GT(totals.operations - totals.refused, 100);
}

TEST(Fuzz, ScriptedBulletSceneNeverLetsAnythingEscape) {
  const FuzzTotals totals = fuzzScene(0x5eed0003, rounds(120), 60);
  std::printf("scene fuzz: %ld actions (%ld refused), %ld substeps, %ld warnings counted\n", totals.operations,
              totals.refused, totals.substeps, totals.warnings);
  EXPECT_GT(totals.substeps, 2000);
  EXPECT_GT(totals.refused, 300);
}

}  // namespace
}  // namespace rope::test
