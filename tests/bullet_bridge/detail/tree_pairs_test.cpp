// SPDX-License-Identifier: MIT
// The tree-tree walk (bullet_bridge/detail/tree_pairs.h) reports exactly the leaf pairs of Bullet's
// own btDbvt::collideTT, for two trees and for a tree with itself, on chains of boxes like a rope's
// (neighbours overlap, some touch exactly) after updates and removals, and none for a NaN box; with a
// filter of subtree pairs, exactly the pairs the filter keeps; and the array forms (every pair of an
// array of leaf boxes, a walk over a tree of them by index) the same pairs again.
#include "bullet_bridge/detail/tree_pairs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "support/fp_exceptions.h"

namespace rope::bullet {
namespace {

using LeafPairs = std::vector<std::pair<int, int>>;

// A random walk of boxes, like a rope's capsule leaves: each next to the one before, so neighbours
// overlap, and the walk folds back on itself, so distant ones do too. Every fifth box is moved to
// touch its predecessor exactly (a shared face), the case the closed test must count.
std::vector<btDbvtNode*> buildChain(btDbvt& tree, std::mt19937_64& random, int count, double offset) {
  std::uniform_real_distribution<double> step(-0.004, 0.004);
  std::vector<btDbvtNode*> leaves;
  btVector3 centre(static_cast<btScalar>(offset), 0, 0);
  btVector3 previousHigh(0, 0, 0);
  for (int i = 0; i < count; ++i) {
    centre += btVector3(static_cast<btScalar>(step(random)), static_cast<btScalar>(step(random)),
                        static_cast<btScalar>(step(random)));
    const btVector3 half(btScalar(0.003), btScalar(0.002), btScalar(0.0025));
    btVector3 low = centre - half, high = centre + half;
    if (i > 0 && i % 5 == 0) {
      const btScalar shift = previousHigh.x() - low.x();  // low.x onto the last box's high.x
      low.setX(low.x() + shift);
      high.setX(high.x() + shift);
    }
    previousHigh = high;
    leaves.push_back(tree.insert(btDbvtVolume::FromMM(low, high), reinterpret_cast<void*>(static_cast<std::size_t>(i))));
    leaves.back()->dataAsInt = i;
  }
  return leaves;
}

LeafPairs bulletPairs(btDbvt& tree0, const btDbvt& tree1, bool self) {
  struct Collect : btDbvt::ICollide {
    void Process(const btDbvtNode* a, const btDbvtNode* b) override { out->emplace_back(a->dataAsInt, b->dataAsInt); }
    LeafPairs* out = nullptr;
  } collect;
  LeafPairs pairs;
  collect.out = &pairs;
  tree0.collideTTpersistentStack(tree0.m_root, self ? tree0.m_root : tree1.m_root, collect);
  return pairs;
}

LeafPairs walkPairs(const btDbvt& tree0, const btDbvt& tree1, bool self, std::vector<DbvtNodePair>& stack) {
  LeafPairs pairs;
  overlappingLeafPairs(tree0.m_root, self ? tree0.m_root : tree1.m_root, stack,
                       [&](const btDbvtNode* a, const btDbvtNode* b) { pairs.emplace_back(a->dataAsInt, b->dataAsInt); });
  return pairs;
}

// The same unordered pairs (self) or ordered pairs (two trees), each once.
void expectSamePairs(LeafPairs walked, LeafPairs expected, bool self) {
  if (self) {
    for (auto* list : {&walked, &expected})
      for (auto& [a, b] : *list)
        if (b < a) std::swap(a, b);
  }
  std::sort(walked.begin(), walked.end());
  std::sort(expected.begin(), expected.end());
  EXPECT_TRUE(std::adjacent_find(walked.begin(), walked.end()) == walked.end()) << "a pair reported twice";
  EXPECT_EQ(walked, expected);
}

TEST(TreePairs, SameLeafPairsAsBulletsCollideTTForATreeWithItselfAndForTwoTrees) {
  std::mt19937_64 random(20261205);
  btDbvt first, second;
  std::vector<btDbvtNode*> leaves0 = buildChain(first, random, 260, 0.0);
  std::mt19937_64 sameWalk(20261205);
  buildChain(second, sameWalk, 120, 0.002);  // along the first one's first 120 boxes, 2 mm aside
  std::vector<DbvtNodePair> stack;
  std::size_t selfPairs = 0, crossPairs = 0;
  std::uniform_real_distribution<double> nudge(-0.002, 0.002);
  for (int round = 0; round < 4; ++round) {
    const LeafPairs self = bulletPairs(first, first, true);
    const LeafPairs cross = bulletPairs(first, second, false);
    expectSamePairs(walkPairs(first, first, true, stack), self, true);
    expectSamePairs(walkPairs(first, second, false, stack), cross, false);
    selfPairs += self.size();
    crossPairs += cross.size();
    // Move a third of the leaves (the tree's shape changes as in a refit) and go again.
    for (std::size_t i = 0; i < leaves0.size(); i += 3) {
      btDbvtVolume volume = leaves0[i]->volume;
      const btVector3 move(static_cast<btScalar>(nudge(random)), static_cast<btScalar>(nudge(random)), 0);
      volume = btDbvtVolume::FromMM(volume.Mins() + move, volume.Maxs() + move);
      first.update(leaves0[i], volume);
    }
  }
  // Not a vacuous comparison: both kinds of pair occur, many times.
  EXPECT_GT(selfPairs, 1000u);
  EXPECT_GT(crossPairs, 100u);
}

// The filter: a pair of subtrees is skipped when the box around both is smaller than `size` along x.
// Monotone, as the self-contact walk's capsule-range filter is (a subtree's box lies inside its
// parent's), so the walk must report exactly the meeting leaf pairs that the filter keeps at the
// leaves themselves.
TEST(TreePairs, AFilteredWalkReportsTheMeetingLeafPairsTheFilterKeeps) {
  std::mt19937_64 random(20261206);
  btDbvt tree, other;
  buildChain(tree, random, 260, 0.0);
  std::mt19937_64 sameWalk(20261206);
  buildChain(other, sameWalk, 120, 0.002);
  std::vector<DbvtNodePair> stack;
  for (const btScalar size : {btScalar(0.007), btScalar(0.009), btScalar(0.011)}) {
    long asked = 0;
    const auto mayPair = [&](const btDbvtNode* a, const btDbvtNode* b) {
      ++asked;
      const btScalar low = std::min(a->volume.Mins().x(), b->volume.Mins().x());
      const btScalar high = std::max(a->volume.Maxs().x(), b->volume.Maxs().x());
      return high - low >= size;
    };
    const auto keptAtLeaves = [&](const btDbvt& tree1, bool self) {
      std::vector<const btDbvtNode*> leaves0, leaves1;
      struct Collect : btDbvt::ICollide {
        void Process(const btDbvtNode* leaf) override { out->push_back(leaf); }
        std::vector<const btDbvtNode*>* out = nullptr;
      } collect;
      collect.out = &leaves0;
      btDbvt::enumLeaves(tree.m_root, collect);
      collect.out = &leaves1;
      btDbvt::enumLeaves(tree1.m_root, collect);
      LeafPairs pairs;
      for (const btDbvtNode* a : leaves0)
        for (const btDbvtNode* b : leaves1) {
          if (self && a->dataAsInt >= b->dataAsInt) continue;
          if (boxesMeet(a->volume, b->volume) && mayPair(a, b)) pairs.emplace_back(a->dataAsInt, b->dataAsInt);
        }
      return pairs;
    };
    for (const bool self : {true, false}) {
      const btDbvt& tree1 = self ? tree : other;
      LeafPairs walked;
      asked = 0;
      overlappingLeafPairs(
          tree.m_root, tree1.m_root, stack,
          [&](const btDbvtNode* a, const btDbvtNode* b) { walked.emplace_back(a->dataAsInt, b->dataAsInt); }, mayPair);
      const long walkAsked = asked;
      const LeafPairs expected = keptAtLeaves(tree1, self);
      expectSamePairs(walked, expected, self);
      // Not vacuous: the filter keeps some meeting pairs and drops others.
      EXPECT_GT(expected.size(), 20u) << "size " << size << (self ? ", self" : ", two trees");
      EXPECT_LT(expected.size(), walkPairs(tree, tree1, self, stack).size()) << "size " << size;
      EXPECT_GT(walkAsked, 0);
    }
  }
}

// The array form (overlappingBoxPairs) of a tree with itself: the walk's pairs, for trees of 4, 16
// and 260 leaves (the small ones as a short rope's), unfiltered and with the monotone filter above.
TEST(TreePairs, AnArrayOfLeafBoxesGivesTheWalksPairs) {
  std::vector<DbvtNodePair> stack;
  for (const int count : {4, 16, 260}) {
    std::mt19937_64 random(20261207 + static_cast<unsigned>(count));
    btDbvt tree;
    const std::vector<btDbvtNode*> leaves = buildChain(tree, random, count, 0.0);
    std::vector<btDbvtVolume> boxes;
    for (const btDbvtNode* leaf : leaves) boxes.push_back(leaf->volume);  // leaf i holds dataAsInt i
    std::size_t unfiltered = 0;
    for (const btScalar size : {btScalar(0), btScalar(0.009)}) {
      const auto spanOf = [&](btScalar low0, btScalar high0, btScalar low1, btScalar high1) {
        return std::max(high0, high1) - std::min(low0, low1) >= size;
      };
      LeafPairs walked, scanned;
      overlappingLeafPairs(
          tree.m_root, tree.m_root, stack,
          [&](const btDbvtNode* a, const btDbvtNode* b) { walked.emplace_back(a->dataAsInt, b->dataAsInt); },
          [&](const btDbvtNode* a, const btDbvtNode* b) {
            return spanOf(a->volume.Mins().x(), a->volume.Maxs().x(), b->volume.Mins().x(), b->volume.Maxs().x());
          });
      overlappingBoxPairs(
          boxes, [&](int i, int j) { scanned.emplace_back(i, j); },
          [&](int i, int j) {
            const btDbvtVolume& a = boxes[static_cast<std::size_t>(i)];
            const btDbvtVolume& b = boxes[static_cast<std::size_t>(j)];
            return spanOf(a.Mins().x(), a.Maxs().x(), b.Mins().x(), b.Maxs().x());
          });
      for (const auto& [i, j] : scanned) EXPECT_LT(i, j);
      expectSamePairs(walked, scanned, true);
      // Not vacuous: neighbours always meet; on the longer chains the filter keeps some pairs and
      // drops others.
      if (size == 0) {
        EXPECT_GE(scanned.size(), static_cast<std::size_t>(count - 1)) << count << " leaves";
        unfiltered = scanned.size();
      } else if (count > 4) {
        EXPECT_GT(scanned.size(), 0u) << count << " leaves";
        EXPECT_LT(scanned.size(), unfiltered) << count << " leaves";
      }
    }
  }
}

// The walk over an indexed tree (selfOverlappingBoxPairs) reports the array scan's pairs, for 0 to
// 260 leaves (odd counts leave one-child nodes at every level), unfiltered and with monotone filters
// of index ranges: a gap along the chain (as the self-contact exclusion) and the x extent of the
// ranges' boxes. One tree is rebuilt for every count (levels reused, larger and smaller).
TEST(TreePairs, AnIndexedTreeOfLeafBoxesGivesTheArrayScansPairs) {
  IndexedBoxTree tree;
  std::vector<IndexedNodePair> stack;
  for (const int count : {260, 0, 1, 2, 3, 5, 17, 100, 33}) {
    std::mt19937_64 random(20261208 + static_cast<unsigned>(count));
    btDbvt dbvt;
    std::vector<btDbvtVolume> boxes;
    for (const btDbvtNode* leaf : buildChain(dbvt, random, count, 0.0)) boxes.push_back(leaf->volume);
    tree.build(boxes);
    EXPECT_EQ(tree.count(), count);
    // Index range [x0, x1] of a node: the union of its boxes along x, for the extent filter.
    const auto extent = [&](int x0, int x1, int y0, int y1) {
      btScalar low = boxes[static_cast<std::size_t>(x0)].Mins().x(), high = boxes[static_cast<std::size_t>(x0)].Maxs().x();
      for (const auto& [first, last] : {std::pair<int, int>(x0, x1), std::pair<int, int>(y0, y1)}) {
        for (int i = first; i <= last; ++i) {
          low = std::min(low, boxes[static_cast<std::size_t>(i)].Mins().x());
          high = std::max(high, boxes[static_cast<std::size_t>(i)].Maxs().x());
        }
      }
      return high - low;
    };
    std::size_t unfiltered = 0;
    for (int filter = 0; filter < 3; ++filter) {
      const auto mayPair = [&](int x0, int x1, int y0, int y1) {
        if (filter == 1) return std::max(y1 - x0, x1 - y0) >= 5;  // the chain's far ends at least 5 apart
        if (filter == 2) return extent(x0, x1, y0, y1) >= btScalar(0.009);
        return true;
      };
      LeafPairs walked, scanned;
      long asked = 0;
      selfOverlappingBoxPairs(
          tree, stack, [&](int i, int j) { walked.emplace_back(i, j); },
          [&](int x0, int x1, int y0, int y1) {
            ++asked;
            EXPECT_LE(x0, x1);
            EXPECT_LE(y0, y1);
            EXPECT_TRUE((x0 == y0 && x1 == y1) || x1 < y0) << x0 << ".." << x1 << " with " << y0 << ".." << y1;
            return mayPair(x0, x1, y0, y1);
          });
      overlappingBoxPairs(boxes, [&](int i, int j) { scanned.emplace_back(i, j); },
                          [&](int i, int j) { return mayPair(i, i, j, j); });
      for (const auto& [i, j] : walked) EXPECT_LT(i, j);
      expectSamePairs(walked, scanned, true);
      if (count < 2) {
        EXPECT_EQ(asked, 0) << count << " leaves";
      }
      // Not vacuous: neighbours always meet; on the longer chains each filter keeps some pairs and
      // drops others.
      if (filter == 0) {
        EXPECT_GE(scanned.size(), static_cast<std::size_t>(std::max(0, count - 1))) << count << " leaves";
        unfiltered = scanned.size();
      } else if (count >= 17) {
        EXPECT_GT(scanned.size(), 0u) << count << " leaves, filter " << filter;
        EXPECT_LT(scanned.size(), unfiltered) << count << " leaves, filter " << filter;
      }
    }
  }
}

TEST(TreePairs, NullAndSingleLeafTreesGiveNoPairsAndANaNBoxMeetsNothing) {
  std::vector<DbvtNodePair> stack;
  btDbvt empty, one;
  const btDbvtNode* leaf = one.insert(btDbvtVolume::FromMM(btVector3(0, 0, 0), btVector3(1, 1, 1)), nullptr);
  EXPECT_TRUE(walkPairs(empty, one, false, stack).empty());
  EXPECT_TRUE(walkPairs(one, one, true, stack).empty());  // a leaf is never paired with itself
  // Two identical boxes meet; with a NaN coordinate they do not (as btDbvt's Intersect).
  const btDbvtVolume box = btDbvtVolume::FromMM(btVector3(0, 0, 0), btVector3(1, 1, 1));
  EXPECT_TRUE(boxesMeet(box, box));
  EXPECT_TRUE(boxesMeet(box, btDbvtVolume::FromMM(btVector3(1, 1, 1), btVector3(2, 2, 2))));  // touching corner
  EXPECT_FALSE(boxesMeet(box, btDbvtVolume::FromMM(btVector3(1.0001, 0, 0), btVector3(2, 1, 1))));
  const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
  // An ordered comparison with a NaN raises the trapped "invalid" exception, as Bullet's own test
  // does; the ropes' trees never hold such a box (CapsuleProxies::fitLeaf keeps the previous leaf).
  const test::ScopedNoFloatingPointTraps noTraps;
  EXPECT_FALSE(boxesMeet(box, btDbvtVolume::FromMM(btVector3(nan, 0, 0), btVector3(1, 1, 1))));
  EXPECT_FALSE(boxesMeet(btDbvtVolume::FromMM(btVector3(0, 0, 0), btVector3(1, nan, 1)), box));
  EXPECT_EQ(leaf->volume.Mins().x(), 0);
}

}  // namespace
}  // namespace rope::bullet
