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

// Every pair whose boxes meet.
template <class Visit>
void overlappingLeafPairs(const btDbvtNode* root0, const btDbvtNode* root1, std::vector<DbvtNodePair>& stack,
                          Visit&& visit) {
  overlappingLeafPairs(root0, root1, stack, std::forward<Visit>(visit),
                       [](const btDbvtNode*, const btDbvtNode*) { return true; });
}

}  // namespace rope::bullet
