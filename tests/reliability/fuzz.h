#pragma once
// The deterministic fuzzers behind fuzz_test.cpp (and the longer soak runs): each draws everything
// from std::mt19937_64 seeded with `seed` (its output sequence is fixed by the C++ standard; the
// helpers below turn raw outputs into numbers without the library's distributions, whose results
// are implementation-defined), and reports an invariant violation as a GoogleTest failure naming
// the round and the operation.

#include <cstdint>

namespace rope::test {

struct FuzzTotals {
  long operations = 0;   // operations, settings tried, or script actions
  long refused = 0;      // calls refused with InvalidArgument (state checked unchanged)
  long insertions = 0;
  long removals = 0;
  long cuts = 0;
  long failedSteps = 0;  // steps reported failed (state kept)
  long substeps = 0;     // Bullet substeps run
  long warnings = 0;     // warnings counted by ropes and rope worlds
};

// `rounds` rods from random polylines, each put through random knot insertions, removals, cuts,
// evaluations and steps (with bad parameters among them).
FuzzTotals fuzzSplineOperations(std::uint64_t seed, int rounds);
// `rounds` random settings of each kind (RodSettings, BulletRopeSettings, KinematicRopeSettings,
// TractrixSettings); accepted ones are simulated for a few steps.
FuzzTotals fuzzSettings(std::uint64_t seed, int rounds);
// `rounds` Bullet scenes, each driven by a script of `actions` random actions.
FuzzTotals fuzzScene(std::uint64_t seed, int rounds, int actions);

}  // namespace rope::test
