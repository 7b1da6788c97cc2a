// SPDX-License-Identifier: MIT
// Corpus replay (issue 17): every input kept in the repository for the libFuzzer targets runs again
// through the same fuzzers driven by bytes (fuzz.h), with the floating-point traps on, so the
// invariants the targets check (fuzz.cpp) are checked here too on every default test run:
//   - corpus/<target>/      the seed corpus, merged from the libFuzzer runs (CONTRIBUTING.md);
//   - regressions/<target>/ every input that once failed (a crash, an escaped exception, a broken
//                           invariant), named after what it found.
// <target> is spline, settings or scene. Each corpus directory must hold at least one input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "reliability/fuzz.h"

namespace rope::test {
namespace {

using Entry = FuzzTotals (*)(const std::uint8_t*, std::size_t);

std::vector<std::filesystem::path> inputsIn(const std::string& directory) {
  std::vector<std::filesystem::path> files;
  const std::filesystem::path root = std::filesystem::path(SPLINEROPE_CORPUS_DIR) / directory;
  if (!std::filesystem::is_directory(root)) return files;
  for (const auto& entry : std::filesystem::directory_iterator(root))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

// Replays every input of the directory; returns how many ran.
int replay(const std::string& directory, Entry entry) {
  int count = 0;
  for (const std::filesystem::path& file : inputsIn(directory)) {
    std::ifstream in(file, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    SCOPED_TRACE(file.string());
    entry(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    ++count;
    if (::testing::Test::HasFailure()) break;
  }
  std::printf("%s: %d inputs replayed\n", directory.c_str(), count);
  return count;
}

TEST(CorpusReplay, Spline) { EXPECT_GT(replay("corpus/spline", fuzzSplineBytes), 0); }
TEST(CorpusReplay, Settings) { EXPECT_GT(replay("corpus/settings", fuzzSettingsBytes), 0); }
TEST(CorpusReplay, Scene) { EXPECT_GT(replay("corpus/scene", fuzzSceneBytes), 0); }

// A target whose fuzzing never failed has no regression input (scene, so far).
TEST(RegressionReplay, EveryInputThatOnceFailed) {
  int count = replay("regressions/spline", fuzzSplineBytes);
  count += replay("regressions/settings", fuzzSettingsBytes);
  count += replay("regressions/scene", fuzzSceneBytes);
  EXPECT_GE(count, 2);  // the two inputs of issue 17's libFuzzer runs
}

}  // namespace
}  // namespace rope::test
