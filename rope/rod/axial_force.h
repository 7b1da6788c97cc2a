// SPDX-License-Identifier: MIT
#pragma once
// The axial force (tension) a rod carries at s, as its stretching law sees it (docs/method.md §7).
//
// The pointwise Green–Lagrange tension T = (EA/2)(γ² − 1)γ at C′(s) is not what the rod's forces are
// made of: the default locking-free rule samples the strain at n − 1 points only, and between them
// the cubic's strain may ripple with no energy (a straight strand carrying 10 N read 10.8 N at its end
// and 4.6 N at the other end of a 5 N strand, where the samples held 10.000 and 5.000 N). The readout
// therefore interpolates the tension at the stretching quadrature points linearly in s, and
// extrapolates the two nearest ones beyond the first or last point (exact for a uniform or linearly
// varying tension, e.g. a hanging rope). With StretchingQuadrature::kExact the points are the span's
// 2d − 1 Gauss points and the readout follows the pointwise tension closely.

#include "rope/rod/rod.h"

namespace rope {

// N, > 0 pulling, < 0 compressed. Throws InvalidArgument("s", ...) for s outside
// [rod.beginParameter(), rod.endParameter()] or NaN. O(d) per call.
double axialForce(const Rod& rod, double s);

}  // namespace rope
