// SPDX-License-Identifier: MIT
// Golden determinism (Box2D's guard, issue 17). Twin runs agreeing bitwise (the scenes' own tests)
// says a run repeats itself; this says it repeats what it did when the hashes were recorded: each
// ropesim scene is simulated for kSeconds and the bits of its full state (DemoScene::appendState:
// rods with knots, velocities, rest curve and pins; tractrix ropes; every Bullet body's transform and
// velocities) are hashed (FNV-1a, 64 bit) and compared with tests/reliability/golden_hashes.txt.
// Any change that alters a trajectory, on purpose or not, changes a hash and fails this test.
//
// When the physics changes on purpose (a new contact law, a different default), regenerate the file
// and say why in CHANGELOG.md in the same commit:
//
//   cmake --build build/release --target reliability_golden_hash_test &&
//   SPLINEROPE_UPDATE_GOLDEN=1 build/release/tests/reliability/reliability_golden_hash_test
//
// which rewrites tests/reliability/golden_hashes.txt in the source tree and prints the new table.
// The hashes hold for the double-precision Bullet build on x86-64 with SSE2 and -ffp-contract=off
// (the project's flags); the float build does not build this test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "demos/scenes/demo_scene.h"

#ifndef SPLINEROPE_GOLDEN_FILE
#error "SPLINEROPE_GOLDEN_FILE must name tests/reliability/golden_hashes.txt"
#endif

namespace rope::demos {
namespace {

// Long enough for every scene's first contacts, self-contacts, attachments, cut and adaptivity.
constexpr double kSeconds = 1.25;

std::uint64_t fnv1a(const std::vector<double>& values) {
  std::uint64_t hash = 0xcbf29ce484222325ull;
  for (const double value : values) {
    unsigned char bytes[sizeof(double)];
    std::memcpy(bytes, &value, sizeof bytes);
    for (const unsigned char byte : bytes) {
      hash ^= byte;
      hash *= 0x100000001b3ull;
    }
  }
  return hash;
}

std::string hex(std::uint64_t value) {
  char text[24];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

std::uint64_t sceneHash(const SceneEntry& entry, int& steps) {
  std::unique_ptr<DemoScene> scene = entry.create();
  steps = static_cast<int>(std::lround(kSeconds / scene->timeStep()));
  for (int i = 0; i < steps; ++i) scene->step();
  std::vector<double> state;
  scene->appendState(state);
  return fnv1a(state);
}

std::map<std::string, std::string> readGolden() {
  std::map<std::string, std::string> table;
  std::ifstream file(SPLINEROPE_GOLDEN_FILE);
  std::string line;
  while (std::getline(file, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string name, hash;
    fields >> name >> hash;
    table[name] = hash;
  }
  return table;
}

TEST(GoldenHash, EveryScenesStateAfterAFixedRunMatchesTheRecordedHash) {
  const bool update = std::getenv("SPLINEROPE_UPDATE_GOLDEN") != nullptr;
  const std::map<std::string, std::string> golden = readGolden();
  std::ostringstream table;
  table << "# Golden determinism hashes (tests/reliability/golden_hash_test.cpp): FNV-1a 64 of the bits of\n"
        << "# DemoScene::appendState after " << kSeconds << " s of each ropesim scene. Regenerate only for an\n"
        << "# intended physics change, with a CHANGELOG.md line saying why (see the test for the command).\n";
  for (const SceneEntry& entry : sceneCatalogue()) {
    int steps = 0;
    const std::string hash = hex(sceneHash(entry, steps));
    table << entry.name << ' ' << hash << '\n';
    std::printf("golden %-9s %s (%d steps)\n", entry.name.c_str(), hash.c_str(), steps);
    if (update) continue;
    const auto recorded = golden.find(entry.name);
    if (recorded == golden.end()) {
      ADD_FAILURE() << entry.name << ": no recorded hash in " << SPLINEROPE_GOLDEN_FILE;
    } else {
      EXPECT_EQ(hash, recorded->second) << entry.name << ": the trajectory changed. If that is intended, "
                                        << "regenerate the hashes (see golden_hash_test.cpp) and say why in "
                                           "CHANGELOG.md";
    }
  }
  if (update) {
    std::ofstream(SPLINEROPE_GOLDEN_FILE) << table.str();
    std::printf("rewrote %s\n", SPLINEROPE_GOLDEN_FILE);
  } else {
    EXPECT_EQ(golden.size(), sceneCatalogue().size()) << "the file lists scenes the catalogue does not have";
  }
}

// The hash sees every part of the state: one ulp anywhere changes it.
TEST(GoldenHash, OneUlpChangesTheHash) {
  std::vector<double> state = {0.0, 1.0, -2.5, 1e-300};
  const std::uint64_t original = fnv1a(state);
  for (std::size_t i = 0; i < state.size(); ++i) {
    std::vector<double> changed = state;
    changed[i] = std::nextafter(changed[i], std::numeric_limits<double>::infinity());
    EXPECT_NE(fnv1a(changed), original) << i;
  }
}

}  // namespace
}  // namespace rope::demos
