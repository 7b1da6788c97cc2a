// SPDX-License-Identifier: MIT
#pragma once
// One runner per engine; rope::compare::run() dispatches to them. Each runs one scene with one
// setting and times only the engine's step calls (measurements are taken outside the timer).

#include "demos/compare/compare.h"

namespace rope::compare {
namespace splinerope { Trial run(Scene scene, const Setting& setting, const Limits& limits); }
namespace softbody { Trial run(Scene scene, const Setting& setting, const Limits& limits); }
namespace mujoco { Trial run(Scene scene, const Setting& setting, const Limits& limits); }
}  // namespace rope::compare
