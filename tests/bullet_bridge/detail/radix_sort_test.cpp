// SPDX-License-Identifier: MIT
#include "bullet_bridge/detail/radix_sort.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "rope/common/error.h"

namespace rope::bullet {
namespace {

std::vector<KeyedIndex> stdStableSorted(std::vector<KeyedIndex> items) {
  std::stable_sort(items.begin(), items.end(), [](const KeyedIndex& a, const KeyedIndex& b) { return a.key < b.key; });
  return items;
}

// Keys and indices in the same order as std::stable_sort's, except that -0 precedes +0 (documented).
void expectSameOrder(const std::vector<KeyedIndex>& sorted, const std::vector<KeyedIndex>& expected) {
  ASSERT_EQ(sorted.size(), expected.size());
  for (size_t i = 0; i < sorted.size(); ++i) {
    EXPECT_EQ(sorted[i].key, expected[i].key) << "at " << i;
    EXPECT_EQ(sorted[i].index, expected[i].index) << "at " << i;
  }
}

TEST(RadixSort, MatchesStableSortOnMixedSignsRepeatsAndInfinities) {
  std::mt19937_64 random(20261205);
  std::uniform_real_distribution<double> gap(-2e-3, 1e-2);
  std::uniform_int_distribution<int> pick(0, 9);
  std::vector<KeyedIndex> items;
  for (int i = 0; i < 5000; ++i) {
    double key = gap(random);
    // Repeats (ties keep their order), whole powers and both infinities.
    if (pick(random) == 0 && !items.empty()) key = items[static_cast<size_t>(i / 2)].key;
    if (i % 997 == 0) key = std::numeric_limits<double>::infinity();
    if (i % 991 == 0) key = -std::numeric_limits<double>::infinity();
    if (i % 499 == 0) key = 1.0;
    if (i % 1013 == 0) key = std::numeric_limits<double>::denorm_min();
    items.push_back({key, i});
  }
  const std::vector<KeyedIndex> expected = stdStableSorted(items);
  std::vector<KeyedIndex> scratch;
  radixSortByKey(items, scratch);
  expectSameOrder(items, expected);
}

TEST(RadixSort, LeadingBytesSortStablyByTheLeadingKeyWhichFollowsTheKeysOrder) {
  std::mt19937_64 random(20261206);
  std::uniform_real_distribution<double> gap(-2e-3, 1e-2);
  std::vector<KeyedIndex> items;
  for (int i = 0; i < 3000; ++i) {
    // Clusters of keys a few ulps apart: they share their leading 4 bytes but not the whole key.
    const double key = i % 3 == 0 || items.empty() ? gap(random) : std::nextafter(items.back().key, 1.0);
    items.push_back({key, i});
  }
  for (const int bytes : {1, 4, 8}) {
    std::vector<KeyedIndex> sorted = items, scratch;
    radixSortByKey(sorted, scratch, bytes);
    std::vector<KeyedIndex> expected = items;
    std::stable_sort(expected.begin(), expected.end(), [&](const KeyedIndex& a, const KeyedIndex& b) {
      return leadingKey(a.key, bytes) < leadingKey(b.key, bytes);
    });
    expectSameOrder(sorted, expected);
  }
  // In order of the keys, never against it; ties only where the key's trailing bytes differ.
  std::vector<KeyedIndex> byKey = stdStableSorted(items);
  int ties = 0;
  for (size_t i = 1; i < byKey.size(); ++i) {
    EXPECT_LE(leadingKey(byKey[i - 1].key, 4), leadingKey(byKey[i].key, 4)) << "at " << i;
    if (byKey[i - 1].key < byKey[i].key && leadingKey(byKey[i - 1].key, 4) == leadingKey(byKey[i].key, 4)) ++ties;
    EXPECT_EQ(leadingKey(byKey[i - 1].key, 8) < leadingKey(byKey[i].key, 8), byKey[i - 1].key < byKey[i].key) << "at " << i;
  }
  EXPECT_GT(ties, 100);  // the clusters tie on 4 bytes
}

TEST(RadixSort, ByteCountsOutsideOneToEightAreRefusedAndSortNothing) {
  std::vector<KeyedIndex> items{{2.0, 0}, {1.0, 1}}, scratch;
  for (const int bytes : {0, 9, -1}) {
    try {
      radixSortByKey(items, scratch, bytes);
      ADD_FAILURE() << "no exception for bytes " << bytes;
    } catch (const InvalidArgument& error) {
      EXPECT_EQ(error.parameter(), "bytes");
    }
    EXPECT_EQ(items[0].index, 0);
    EXPECT_THROW(leadingKey(1.0, bytes), InvalidArgument);
  }
}

TEST(RadixSort, NegativeZeroComesJustBeforePositiveZero) {
  std::vector<KeyedIndex> items{{0.0, 0}, {-1e-300, 1}, {-0.0, 2}, {1e-300, 3}, {0.0, 4}, {-0.0, 5}};
  std::vector<KeyedIndex> scratch;
  radixSortByKey(items, scratch);
  const std::vector<int> order{1, 2, 5, 0, 4, 3};
  for (size_t i = 0; i < order.size(); ++i) EXPECT_EQ(items[i].index, order[i]) << "at " << i;
  EXPECT_TRUE(std::signbit(items[1].key));
  EXPECT_FALSE(std::signbit(items[3].key));
}

TEST(RadixSort, ShortAndConstantInputsAndReusedScratch) {
  std::vector<KeyedIndex> scratch;
  std::vector<KeyedIndex> none;
  radixSortByKey(none, scratch);
  EXPECT_TRUE(none.empty());
  std::vector<KeyedIndex> one{{3.0, 7}};
  radixSortByKey(one, scratch);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].index, 7);
  // Every byte shared: every pass is skipped and the order is the input's.
  std::vector<KeyedIndex> same{{0.25, 2}, {0.25, 0}, {0.25, 1}};
  radixSortByKey(same, scratch);
  EXPECT_EQ(same[0].index, 2);
  EXPECT_EQ(same[1].index, 0);
  EXPECT_EQ(same[2].index, 1);
  // Scratch left from a longer sort, and an odd number of passes (the result in the caller's vector).
  std::vector<KeyedIndex> two{{2.0, 0}, {1.0, 1}};
  radixSortByKey(two, scratch);
  EXPECT_EQ(two[0].index, 1);
  EXPECT_EQ(two[1].index, 0);
}

}  // namespace
}  // namespace rope::bullet
