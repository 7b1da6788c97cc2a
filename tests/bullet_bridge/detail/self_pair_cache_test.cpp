// SPDX-License-Identifier: MIT
// The kept self-contact pairs (bullet_bridge/detail/self_pair_cache.h) are, after every move, exactly
// the pairs a fresh scan of the current boxes finds (filtered by a gap along the chain that depends on
// a key): while the boxes creep within the slack the pairs are kept, and a box that leaves its grown
// box, a changed key or a changed box count makes them be found again.
#include "bullet_bridge/detail/self_pair_cache.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

namespace rope::bullet {
namespace {

using Pairs = std::vector<std::pair<int, int>>;

// A folded chain of boxes like a rope's capsules (tree_pairs_test.cpp: neighbours overlap, distant
// ones meet where the walk folds back).
std::vector<btVector3> chainCentres(std::mt19937_64& random, int count) {
  std::uniform_real_distribution<double> step(-0.004, 0.004);
  std::vector<btVector3> centres;
  btVector3 centre(0, 0, 0);
  for (int i = 0; i < count; ++i) {
    centre += btVector3(static_cast<btScalar>(step(random)), static_cast<btScalar>(step(random)),
                        static_cast<btScalar>(step(random)));
    centres.push_back(centre);
  }
  return centres;
}

std::vector<btDbvtVolume> boxesAt(const std::vector<btVector3>& centres) {
  const btVector3 half(btScalar(0.003), btScalar(0.002), btScalar(0.0025));
  std::vector<btDbvtVolume> boxes;
  for (const btVector3& centre : centres) boxes.push_back(btDbvtVolume::FromMM(centre - half, centre + half));
  return boxes;
}

Pairs sorted(Pairs pairs) {
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

TEST(SelfPairCache, ReportsTheScansPairsAfterEveryMoveAndKeepsThemOnlyWhileTheyHold) {
  std::mt19937_64 random(20261206);
  std::vector<btVector3> centres = chainCentres(random, 200);
  const btScalar slack = btScalar(0.001);
  // The filter's key: its first entry is the gap (in indices) below which two boxes never pair.
  std::vector<double> key = {4.0};
  const auto mayPair = [&](int x0, int x1, int y0, int y1) { return std::max(y1 - x0, x1 - y0) >= static_cast<int>(key[0]); };
  SelfPairCache cache;
  IndexedBoxTree tree;
  std::vector<IndexedNodePair> stack;
  int reused = 0, walked = 0, changedWhileKept = 0;
  Pairs previous;
  // Each round: creeping moves (well within the slack), then a jump of one box, a changed key, a
  // changed count. The expected flag says whether the pairs may be kept.
  std::uniform_real_distribution<double> creep(-0.00005, 0.00005);
  for (int round = 0; round < 60; ++round) {
    bool mayKeep = round > 0;
    const int phase = round % 10;
    if (phase == 3) {
      centres[static_cast<std::size_t>(round) % centres.size()] += btVector3(btScalar(0.0015), 0, 0);  // out of its grown box
      mayKeep = false;
    } else if (phase == 6) {
      key[0] = key[0] == 4.0 ? 6.0 : 4.0;
      mayKeep = false;
    } else if (phase == 9) {
      centres.pop_back();
      mayKeep = false;
    } else {
      for (btVector3& centre : centres) {
        centre += btVector3(static_cast<btScalar>(creep(random)), static_cast<btScalar>(creep(random)),
                            static_cast<btScalar>(creep(random)));
      }
    }
    const std::vector<btDbvtVolume> boxes = boxesAt(centres);
    Pairs found, scanned;
    cache.find(boxes, key, slack, tree, stack, [&](int i, int j) { found.emplace_back(i, j); }, mayPair);
    overlappingBoxPairs(boxes, [&](int i, int j) { scanned.emplace_back(i, j); },
                        [&](int i, int j) { return mayPair(i, i, j, j); });
    EXPECT_EQ(sorted(found), sorted(scanned)) << "round " << round;
    for (const auto& [i, j] : found) EXPECT_LT(i, j);
    if (!mayKeep) {
      EXPECT_FALSE(cache.reused()) << "round " << round;
    }
    (cache.reused() ? reused : walked) += 1;
    if (cache.reused() && sorted(found) != previous) ++changedWhileKept;
    previous = sorted(found);
  }
  // Not vacuous: the chain folds (far pairs exist), creeping keeps the pairs, and the pairs changed
  // while kept (the creeping moves open and close some of them).
  EXPECT_GT(reused, 30);
  EXPECT_GE(walked, 19);
  EXPECT_GT(changedWhileKept, 0);
  EXPECT_GT(previous.size(), centres.size());
}

TEST(SelfPairCache, KeptPairsThatStopMeetingAreNotReportedAndClearForgetsThem) {
  // Two far boxes of a chain of three meet, then part by less than the slack: the pairs are kept
  // but the parted pair is not reported.
  std::vector<btVector3> centres = {btVector3(0, 0, 0), btVector3(btScalar(0.1), 0, 0), btVector3(btScalar(0.0055), 0, 0)};
  const std::vector<double> key;
  const auto mayPair = [](int, int, int, int) { return true; };
  SelfPairCache cache;
  IndexedBoxTree tree;
  std::vector<IndexedNodePair> stack;
  Pairs found;
  const auto collect = [&](int i, int j) { found.emplace_back(i, j); };
  cache.find(boxesAt(centres), key, btScalar(0.002), tree, stack, collect, mayPair);
  EXPECT_EQ(found, (Pairs{{0, 2}}));
  EXPECT_FALSE(cache.reused());
  found.clear();
  centres[2] = btVector3(btScalar(0.0065), 0, 0);  // 0.5 mm apart now, 1 mm moved
  cache.find(boxesAt(centres), key, btScalar(0.002), tree, stack, collect, mayPair);
  EXPECT_TRUE(cache.reused());
  EXPECT_TRUE(found.empty());
  found.clear();
  cache.clear();
  cache.find(boxesAt(centres), key, btScalar(0.002), tree, stack, collect, mayPair);
  EXPECT_FALSE(cache.reused());
  EXPECT_TRUE(found.empty());
}

}  // namespace
}  // namespace rope::bullet
