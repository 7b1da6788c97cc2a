// SPDX-License-Identifier: MIT
#pragma once
// The fuzzers behind fuzz_test.cpp, the soak runs, the libFuzzer targets (fuzz_targets/) and the
// corpus replay (corpus_test.cpp). One logic, two sources of choices:
//   - seeded: every choice from std::mt19937_64 (its output sequence is fixed by the C++ standard;
//     fuzz.cpp turns raw outputs into numbers without <random>'s distributions, whose results are
//     implementation-defined), for the deterministic runs in the default tests;
//   - bytes: every choice read from an input (a libFuzzer input or a corpus file), one byte for a
//     choice among at most 256 and four for a number, zeros once the bytes run out (the script ends).
// An invariant violation is a GoogleTest failure naming the round and the operation (the libFuzzer
// targets turn it into an abort, so libFuzzer keeps the input).

#include <cstddef>
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

// The same fuzzers driven by bytes: one rod and up to 64 operations; one settings struct (its kind
// from the first byte; accepted ones simulated for 2 substeps instead of 10, so that libFuzzer runs
// a million of them in a reasonable time); one scene and up to 48 actions.
FuzzTotals fuzzSplineBytes(const std::uint8_t* data, std::size_t size);
FuzzTotals fuzzSettingsBytes(const std::uint8_t* data, std::size_t size);
FuzzTotals fuzzSceneBytes(const std::uint8_t* data, std::size_t size);

}  // namespace rope::test
