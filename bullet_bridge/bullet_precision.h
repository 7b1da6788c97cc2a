// SPDX-License-Identifier: MIT
#pragma once
// Precision guard. Debian ships one set of Bullet headers for a float and a double build; only
// BT_USE_DOUBLE_PRECISION selects the btScalar layout. Code compiled with the other setting than
// this library would link (most collision APIs take btScalar only by reference) and then corrupt
// memory. Every public bridge header includes this file, and every translation unit that includes
// it references a symbol whose name spells the precision it was compiled with. The library defines
// only the symbol of the precision it was built with, so a mismatch fails to link with
// "undefined reference to splinerope_bullet_built_with_float" (or ..._double).

#include <LinearMath/btScalar.h>

extern "C" {
#if defined(BT_USE_DOUBLE_PRECISION)
extern const int splinerope_bullet_built_with_double;
#else
extern const int splinerope_bullet_built_with_float;
#endif
}

namespace rope::bullet::detail {

// `used` keeps the reference (and its relocation) in every object file even though nothing reads
// it, so an optimising compiler cannot drop the check.
#if defined(BT_USE_DOUBLE_PRECISION)
[[gnu::used]] static const int* const kBulletPrecisionGuard = &splinerope_bullet_built_with_double;
#else
[[gnu::used]] static const int* const kBulletPrecisionGuard = &splinerope_bullet_built_with_float;
#endif

}  // namespace rope::bullet::detail
