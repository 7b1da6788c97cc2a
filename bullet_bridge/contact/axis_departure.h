// SPDX-License-Identifier: MIT
#pragma once
// How far a rope capsule's axis (the chord the midphase and the rope-rope narrowphase use) departs from
// the curve it stands for: a bound per capsule, so that the axes' gap less both bounds is a lower bound
// of the curves' gap (rope-rope thinning, rope_rope_contact.cpp; docs/method.md §12).
// Not API: an internal header of the bridge.

#include <vector>

#include "rope/rod/rod.h"
#include "rope/spline/bspline_curve.h"

namespace rope::bullet {

class CapsuleProxies;

// deviation[i] (resized to proxies.size()) >= |a_i + t (b_i - a_i) - C(s0_i + t (s1_i - s0_i))| for every
// t in [0, 1], m, for capsule i of `proxies` (rebuilt from `rod`; a_i, b_i its axis ends, [s0_i, s1_i]
// its parameters); infinity where no bound is known (degree above 3, or C' jumping at s1_i).
// roundoff: a bound of the rounding in a distance between two axis points (btScalar), m. `ends` is
// scratch (the curve at each capsule end).
void boundAxisDeparture(const Rod& rod, const CapsuleProxies& proxies, std::vector<CurvePoint>& ends,
                        std::vector<double>& deviation, double& roundoff);

}  // namespace rope::bullet
