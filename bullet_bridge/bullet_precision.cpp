// SPDX-License-Identifier: MIT
#include "bullet_bridge/bullet_precision.h"

// The one definition: only the precision this library was compiled with exists at link time.
extern "C" {
#if defined(BT_USE_DOUBLE_PRECISION)
const int splinerope_bullet_built_with_double = 1;
#else
const int splinerope_bullet_built_with_float = 1;
#endif
}
