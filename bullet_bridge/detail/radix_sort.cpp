// SPDX-License-Identifier: MIT
#include "bullet_bridge/detail/radix_sort.h"

#include <array>
#include <cstring>
#include <string>

#include "rope/common/error.h"

namespace rope::bullet {

namespace {

// The IEEE 754 bit pattern of x as an unsigned integer ordered like x (-0 just below +0).
std::uint64_t orderedBits(double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  constexpr std::uint64_t kSign = std::uint64_t{1} << 63;
  return (bits & kSign) != 0 ? ~bits : bits | kSign;
}

void requireBytes(int bytes) {
  if (bytes < 1 || bytes > 8) throw InvalidArgument("bytes", std::to_string(bytes), "must be in [1, 8]");
}

}  // namespace

std::uint64_t leadingKey(double key, int bytes) {
  requireBytes(bytes);
  return orderedBits(key) >> (8 * (8 - bytes));
}

void radixSortByKey(std::vector<KeyedIndex>& items, std::vector<KeyedIndex>& scratch, int bytes) {
  requireBytes(bytes);
  const size_t n = items.size();
  if (n < 2) return;
  scratch.resize(n);
  std::array<std::array<size_t, 256>, 8> counts{};
  for (const KeyedIndex& item : items) {
    const std::uint64_t bits = orderedBits(item.key);
    for (int digit = 8 - bytes; digit < 8; ++digit) ++counts[static_cast<size_t>(digit)][(bits >> (8 * digit)) & 0xff];
  }
  std::vector<KeyedIndex>* from = &items;
  std::vector<KeyedIndex>* to = &scratch;
  for (int digit = 8 - bytes; digit < 8; ++digit) {
    std::array<size_t, 256>& count = counts[static_cast<size_t>(digit)];
    const std::uint64_t first = (orderedBits((*from)[0].key) >> (8 * digit)) & 0xff;
    if (count[first] == n) continue;  // every key has this byte: the pass would change nothing
    size_t start = 0;
    for (size_t& c : count) {
      const size_t bucket = c;
      c = start;
      start += bucket;
    }
    for (const KeyedIndex& item : *from) (*to)[count[(orderedBits(item.key) >> (8 * digit)) & 0xff]++] = item;
    std::swap(from, to);
  }
  if (from != &items) items.swap(scratch);
}

}  // namespace rope::bullet
