// SPDX-License-Identifier: MIT
#pragma once
// Rest arclength along a rod (m from its start, at rest), as the rope's contact rules measure it: the
// self-contact exclusion and the spacing of rope-rope contacts (docs/method.md §12). Not API: an
// internal header of the bridge.

#include <vector>

#include "rope/rod/rod.h"

namespace rope::bullet {

// Cumulative rest length at the start of every knot span of the rod (span j = knot span degree + j)
// and at its end (spanCount + 1 values, into `starts`), so that the rest arclength at a parameter
// costs one span search (restArcAt).
void buildRestArc(const Rod& rod, std::vector<double>& starts);

// Rest arclength from the rod's start to C(s), from `starts` (buildRestArc of the same rod): linear in
// s inside a span, which is exact for ropes made from a segment, whose parameter is the rest arclength.
double restArcAt(const Rod& rod, const std::vector<double>& starts, double s);

}  // namespace rope::bullet
