// SPDX-License-Identifier: MIT
#pragma once
// The leaf pairs of two btDbvt trees, or of one tree with itself, whose boxes meet: the walk of
// btDbvt::collideTT, for the ropes' capsule trees (rope-rope and self-contact candidates). It reports
// exactly the pairs collideTT reports (the same closed-box test; a box with a NaN meets nothing), in
// its own order, which the caller sorts anyway. Why not Bullet's walk: in the double-precision build
// its box test is six short-circuit comparisons, whose mispredicted branches were a third of the
// walk's time in a tight knot (3,400 leaf pairs per substep), and every leaf pair cost a virtual
// call. This one combines the comparisons without branching, tests child pairs before stacking them
// and calls the visitor inline. Not API: an internal header of the bridge.

#include <BulletCollision/BroadphaseCollision/btDbvt.h>

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace rope::bullet {

using DbvtNodePair = std::pair<const btDbvtNode*, const btDbvtNode*>;

// Whether two closed boxes meet (touching counts), as btDbvt's Intersect; false if either has a NaN
// (which, as in Bullet's test, raises FE_INVALID: the ropes' trees never hold such a box, since
// CapsuleProxies::fitLeaf keeps the previous leaf instead).
inline bool boxesMeet(const btDbvtVolume& a, const btDbvtVolume& b) {
  const btVector3& aLow = a.Mins();
  const btVector3& aHigh = a.Maxs();
  const btVector3& bLow = b.Mins();
  const btVector3& bHigh = b.Maxs();
  // Bitwise & of the six comparisons: no branch per comparison (the && of btDbvt's scalar path).
  return static_cast<bool>((aLow.x() <= bHigh.x()) & (aHigh.x() >= bLow.x()) & (aLow.y() <= bHigh.y()) &
                           (aHigh.y() >= bLow.y()) & (aLow.z() <= bHigh.z()) & (aHigh.z() >= bLow.z()));
}

// Calls visit(leaf0, leaf1) for every pair of a leaf of root0's tree and a leaf of root1's tree whose
// boxes meet, except those below a pair of nodes (node0, node1) for which mayPair(node0, node1) is
// false (node0 == node1: the pairs of two leaves below that one node); mayPair is asked only about
// nodes whose boxes meet. With root0 == root1, every unordered pair of two different leaves of the
// tree once (leaf0 and leaf1 in no particular order; a leaf is never paired with itself). Null
// roots: nothing. `stack` is the walk's scratch (its contents are lost; no allocation once it has
// grown).
template <class Visit, class MayPair>
void overlappingLeafPairs(const btDbvtNode* root0, const btDbvtNode* root1, std::vector<DbvtNodePair>& stack,
                          Visit&& visit, MayPair&& mayPair) {
  if (root0 == nullptr || root1 == nullptr) return;
  if (root0 != root1 && !boxesMeet(root0->volume, root1->volume)) return;
  if (!mayPair(root0, root1)) return;
  // The stack by hand: a size check per push instead of a call to emplace_back (which the compiler
  // kept out of line, 1.9 % of the knot step).
  if (stack.size() < 64) stack.resize(64);
  std::size_t depth = 0;
  const auto push = [&](const btDbvtNode* a, const btDbvtNode* b) {
    if (depth == stack.size()) stack.resize(2 * depth);
    stack[depth++] = DbvtNodePair(a, b);
  };
  push(root0, root1);
  // On the stack: one subtree with itself, or two whose boxes meet.
  while (depth > 0) {
    const DbvtNodePair top = stack[--depth];
    const btDbvtNode* a = top.first;
    const btDbvtNode* b = top.second;
    if (a == b) {
      if (a->isleaf()) continue;
      const btDbvtNode* left = a->childs[0];
      const btDbvtNode* right = a->childs[1];
      if (mayPair(left, left)) push(left, left);
      if (mayPair(right, right)) push(right, right);
      if (boxesMeet(left->volume, right->volume) && mayPair(left, right)) push(left, right);
    } else if (a->isleaf() && b->isleaf()) {
      visit(a, b);
    } else if (b->isleaf()) {
      for (const btDbvtNode* child : a->childs)
        if (boxesMeet(child->volume, b->volume) && mayPair(child, b)) push(child, b);
    } else if (a->isleaf()) {
      for (const btDbvtNode* child : b->childs)
        if (boxesMeet(a->volume, child->volume) && mayPair(a, child)) push(a, child);
    } else {
      for (const btDbvtNode* childA : a->childs)
        for (const btDbvtNode* childB : b->childs)
          if (boxesMeet(childA->volume, childB->volume) && mayPair(childA, childB)) push(childA, childB);
    }
  }
}

// What overlappingLeafPairs(root, root, stack, visit, mayPair) reports for a tree whose leaf i
// (dataAsInt i) holds boxes[i], found by testing every pair of the array: visit(i, j) for each
// i < j whose boxes meet and that mayPair(i, j) keeps. The same pairs (in another order) when mayPair
// of two subtrees holds whenever it holds for two leaves below them, as a filter by capsule ranges
// does: the walk asks it of nodes, this of leaves. For a small tree, whose nodes Bullet allocates one
// by one, so that the walk fetches each from wherever it lies.
template <class Visit, class MayPair>
void overlappingBoxPairs(const std::vector<btDbvtVolume>& boxes, Visit&& visit, MayPair&& mayPair) {
  const int count = static_cast<int>(boxes.size());
  for (int i = 0; i < count; ++i)
    for (int j = i + 1; j < count; ++j)
      if (boxesMeet(boxes[static_cast<std::size_t>(i)], boxes[static_cast<std::size_t>(j)]) && mayPair(i, j)) visit(i, j);
}

// A binary tree over boxes in index order, held as one array per level: level 0 is the boxes
// themselves (the caller's array, not copied), and node j of level k + 1 is the union of nodes 2j and
// 2j + 1 of level k (node 2j alone at an odd end), so node j of level k holds the indices
// [j 2^k, min((j + 1) 2^k, count) - 1]. For a long rope's self-contact walk (selfOverlappingBoxPairs)
// instead of its btDbvt: the capsules follow one another along the curve, so index ranges make tight
// nodes; a filter by capsule range drops whole subtrees of neighbours at once; and the walk reads
// arrays, where Bullet's tree is nodes allocated one by one and shaped by the order of insertion.
class IndexedBoxTree {
 public:
  // The levels above `leaves`, which must stay unchanged and alive while the tree is walked. O(n);
  // no allocation once the levels have grown.
  void build(const std::vector<btDbvtVolume>& leaves) {
    leaves_ = &leaves;
    levelCount_ = 0;
    for (std::size_t size = leaves.size(); size > 1; size = (size + 1) / 2) ++levelCount_;
    // All levels first: a level added later would move those before it (`below` points into them).
    if (levels_.size() < static_cast<std::size_t>(levelCount_)) levels_.resize(static_cast<std::size_t>(levelCount_));
    const std::vector<btDbvtVolume>* below = &leaves;
    for (int k = 0; k < levelCount_; ++k) {
      std::vector<btDbvtVolume>& level = levels_[static_cast<std::size_t>(k)];
      level.resize((below->size() + 1) / 2);
      for (std::size_t j = 0; j < level.size(); ++j) {
        const btDbvtVolume& left = (*below)[2 * j];
        if (2 * j + 1 == below->size()) {
          level[j] = left;
          continue;
        }
        const btDbvtVolume& right = (*below)[2 * j + 1];
        btVector3 low = left.Mins(), high = left.Maxs();
        low.setMin(right.Mins());
        high.setMax(right.Maxs());
        level[j] = btDbvtVolume::FromMM(low, high);
      }
      below = &level;
    }
  }
  int count() const { return leaves_ == nullptr ? 0 : static_cast<int>(leaves_->size()); }
  int top() const { return levelCount_; }  // the root's level (0: at most one box)
  int nodes(int level) const {
    return static_cast<int>(level == 0 ? leaves_->size() : levels_[static_cast<std::size_t>(level) - 1].size());
  }
  const btDbvtVolume& box(int level, int node) const {
    return level == 0 ? (*leaves_)[static_cast<std::size_t>(node)]
                      : levels_[static_cast<std::size_t>(level) - 1][static_cast<std::size_t>(node)];
  }
  int first(int level, int node) const { return node << level; }
  int last(int level, int node) const { return std::min(((node + 1) << level) - 1, count() - 1); }

 private:
  const std::vector<btDbvtVolume>* leaves_ = nullptr;
  std::vector<std::vector<btDbvtVolume>> levels_;  // levels_[k - 1] is level k
  int levelCount_ = 0;
};

struct IndexedNodePair {
  int level;
  int a, b;  // nodes of that level, a <= b
};

// What overlappingBoxPairs(leaves, visit, mayPair) reports, by walking `tree` (built over those
// leaves): visit(i, j) for each i < j whose boxes meet and that mayPair(i, i, j, j) keeps, in the
// walk's order. mayPair(first0, last0, first1, last1) is asked of index ranges (two nodes'; first0
// <= last0 < first1 <= last1 unless both are one node), and must hold for two ranges whenever it
// holds for two indices within them, as a filter by capsule ranges does; it is asked only of nodes
// whose boxes meet. `stack` is the walk's scratch (no allocation once it has grown).
template <class Visit, class MayPair>
void selfOverlappingBoxPairs(const IndexedBoxTree& tree, std::vector<IndexedNodePair>& stack, Visit&& visit,
                             MayPair&& mayPair) {
  if (tree.count() < 2) return;
  const auto mayPairNodes = [&](int level, int a, int b) {
    return mayPair(tree.first(level, a), tree.last(level, a), tree.first(level, b), tree.last(level, b));
  };
  const int top = tree.top();  // > 0: two leaves at least
  if (!mayPairNodes(top, 0, 0)) return;
  if (stack.size() < 64) stack.resize(64);
  std::size_t depth = 0;
  // A pair of two leaves is visited at once rather than stacked (most pushes are of leaves).
  const auto push = [&](int level, int a, int b) {
    if (level == 0 && a != b) {
      visit(a, b);
      return;
    }
    if (depth == stack.size()) stack.resize(2 * depth);
    stack[depth++] = IndexedNodePair{level, a, b};
  };
  push(top, 0, 0);
  // On the stack: one node with itself, or two of one level whose boxes meet.
  while (depth > 0) {
    const IndexedNodePair pair = stack[--depth];
    const int level = pair.level;
    if (pair.a == pair.b) {
      const int left = 2 * pair.a, right = left + 1;  // level > 0: a leaf alone is never stacked
      if (level > 1 && mayPairNodes(level - 1, left, left)) push(level - 1, left, left);
      if (right == tree.nodes(level - 1)) continue;  // an odd end: one child
      if (level > 1 && mayPairNodes(level - 1, right, right)) push(level - 1, right, right);
      if (boxesMeet(tree.box(level - 1, left), tree.box(level - 1, right)) && mayPairNodes(level - 1, left, right)) {
        push(level - 1, left, right);
      }
    } else {  // level > 0: leaf pairs are never stacked
      const int childCount = tree.nodes(level - 1);
      for (int childA = 2 * pair.a; childA <= 2 * pair.a + 1; ++childA) {  // a < b: childA never past the end
        for (int childB = 2 * pair.b; childB <= 2 * pair.b + 1 && childB < childCount; ++childB) {
          if (boxesMeet(tree.box(level - 1, childA), tree.box(level - 1, childB)) &&
              mayPairNodes(level - 1, childA, childB)) {
            push(level - 1, childA, childB);
          }
        }
      }
    }
  }
}

// Every pair whose boxes meet.
template <class Visit>
void overlappingLeafPairs(const btDbvtNode* root0, const btDbvtNode* root1, std::vector<DbvtNodePair>& stack,
                          Visit&& visit) {
  overlappingLeafPairs(root0, root1, stack, std::forward<Visit>(visit),
                       [](const btDbvtNode*, const btDbvtNode*) { return true; });
}

}  // namespace rope::bullet
