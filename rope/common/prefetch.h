// SPDX-License-Identifier: MIT
#pragma once
// Cache prefetch hints for data that will be read soon. A RopeWorld steps its ropes one after the
// other, each rope's state (a few hundred 64-byte lines in some thirty heap blocks) read once per
// substep; with a thousand ropes that state no longer stays in the caches from one substep to the
// next, and each block's first read waited ~100 ns for memory. Asking for the next rope's blocks
// while the current one is stepped (~20 us per rope) hides that wait. A hint only: it changes no
// value, and costs one instruction per line.

#include <cstddef>
#include <vector>

namespace rope {

constexpr std::size_t kCacheLineBytes = 64;

// [data, data + bytes), one hint per cache line.
inline void prefetchBytes(const void* data, std::size_t bytes) {
  const char* p = static_cast<const char*>(data);
  for (std::size_t offset = 0; offset < bytes; offset += kCacheLineBytes) __builtin_prefetch(p + offset);
}

// A vector's elements (not its unused capacity).
template <class T, class A>
void prefetchVector(const std::vector<T, A>& v) {
  if (!v.empty()) prefetchBytes(v.data(), v.size() * sizeof(T));
}

}  // namespace rope
