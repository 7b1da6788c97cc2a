// SPDX-License-Identifier: MIT
#pragma once
// Bad input names the parameter: each case changes the default settings in one way, and `use` (a
// constructor, a validate() call, ...) must then throw rope::InvalidArgument whose parameter() is
// exactly the one the case names.
//
//   expectEachRejected<CutSceneSettings>(
//       {{"settings.cutFraction", [](CutSceneSettings& s) { s.cutFraction = 1.0; }}},
//       [](const CutSceneSettings& s) { CutScene scene(s); });

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "rope/common/error.h"

namespace rope::test {

template <class Settings>
struct BadSetting {
  std::string parameter;                  // what the error must name, e.g. "settings.friction"
  std::function<void(Settings&)> change;  // applied to value-initialised settings
};

template <class Settings, class Use>
void expectEachRejected(const std::vector<BadSetting<Settings>>& cases, Use use) {
  for (const BadSetting<Settings>& bad : cases) {
    Settings settings{};
    bad.change(settings);
    try {
      use(settings);
      ADD_FAILURE() << bad.parameter << ": the bad value was accepted";
    } catch (const InvalidArgument& error) {
      EXPECT_EQ(error.parameter(), bad.parameter) << error.what();
    }
  }
}

}  // namespace rope::test
