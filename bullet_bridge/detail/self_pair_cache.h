// SPDX-License-Identifier: MIT
#pragma once
// A long rope's self-contact candidates (RopeWorld::findSelfPairs), kept from one substep to the
// next. Why: a rope that lies still (a heap on the ground) finds the same few thousand capsule pairs
// every substep, and the walk that finds them was 7.5 % of the 2 m pile's step (perf). Bullet's
// broadphase keeps its pairs the same way: each box is stored grown by a slack, and the pairs of the
// grown boxes stay valid while every box stays inside its grown one.
//
// What it reports is exactly what the walk over the current boxes reports (the same pairs; the order
// is its own, and the caller sorts them anyway): the walk over the grown boxes finds a superset, and
// each substep keeps those whose current boxes meet. That holds while
//   - every current box lies inside its grown box (then current boxes that meet have grown boxes that
//     meet), and
//   - the filter (mayPair) is the same: it may depend on nothing but the key, compared bit for bit
//     (for a rope: its capsules' rest arclengths and the self-contact exclusion).
// Otherwise the pairs are found again from the current boxes grown by the slack. Not API: an internal
// header of the bridge.

#include <BulletCollision/BroadphaseCollision/btDbvt.h>

#include <cstddef>
#include <cstring>
#include <utility>
#include <vector>

#include "bullet_bridge/detail/tree_pairs.h"

namespace rope::bullet {

class SelfPairCache {
 public:
  // Calls visit(i, j) for each i < j whose boxes meet and that mayPair(i, i, j, j) keeps: what
  // selfOverlappingBoxPairs reports for a tree over `boxes` (mayPair as there: asked of index ranges,
  // holding for two ranges whenever it holds for two indices within them). `slack` (m, >= 0) is how
  // far the kept boxes are grown: larger keeps the pairs through more motion but keeps more pairs to
  // test. `tree` and `stack` are the walk's scratch.
  template <class Visit, class MayPair>
  void find(const std::vector<btDbvtVolume>& boxes, const std::vector<double>& key, btScalar slack, IndexedBoxTree& tree,
            std::vector<IndexedNodePair>& stack, Visit&& visit, MayPair&& mayPair) {
    reused_ = valid_ && holds(boxes, key);
    if (!reused_) {
      valid_ = false;  // until the pairs below are complete
      const btVector3 grow(slack, slack, slack);
      grown_.resize(boxes.size());
      for (std::size_t i = 0; i < boxes.size(); ++i) {
        grown_[i] = btDbvtVolume::FromMM(boxes[i].Mins() - grow, boxes[i].Maxs() + grow);
      }
      key_ = key;
      pairs_.clear();
      tree.build(grown_);
      selfOverlappingBoxPairs(tree, stack, [&](int i, int j) { pairs_.emplace_back(i, j); }, mayPair);
      valid_ = true;
    }
    for (const std::pair<int, int>& pair : pairs_) {
      if (boxesMeet(boxes[static_cast<std::size_t>(pair.first)], boxes[static_cast<std::size_t>(pair.second)])) {
        visit(pair.first, pair.second);
      }
    }
  }

  // Whether the last find() kept the pairs of the one before (for tests and profiles).
  bool reused() const { return reused_; }
  // Forget the pairs (the next find() walks again).
  void clear() { valid_ = false; }

 private:
  bool holds(const std::vector<btDbvtVolume>& boxes, const std::vector<double>& key) const {
    if (boxes.size() != grown_.size() || key.size() != key_.size()) return false;
    if (!key.empty() && std::memcmp(key.data(), key_.data(), key.size() * sizeof(double)) != 0) return false;
    bool inside = true;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      const btVector3& low = boxes[i].Mins();
      const btVector3& high = boxes[i].Maxs();
      const btVector3& grownLow = grown_[i].Mins();
      const btVector3& grownHigh = grown_[i].Maxs();
      // Bitwise & as in boxesMeet: no branch per comparison. A NaN box is inside nothing.
      inside &= static_cast<bool>((grownLow.x() <= low.x()) & (grownLow.y() <= low.y()) & (grownLow.z() <= low.z()) &
                                  (grownHigh.x() >= high.x()) & (grownHigh.y() >= high.y()) &
                                  (grownHigh.z() >= high.z()));
    }
    return inside;
  }

  std::vector<btDbvtVolume> grown_;  // the boxes of the last walk, grown by its slack
  std::vector<double> key_;          // the filter's key at the last walk
  std::vector<std::pair<int, int>> pairs_;  // what the last walk reported, over grown_
  bool valid_ = false;
  bool reused_ = false;
};

}  // namespace rope::bullet
