// SPDX-License-Identifier: MIT
#pragma once
// Closed-form tractrix motion of one rigid segment ([B] §2.1 eq. 1; docs/method.md §13, eqs. 38–40).
//
// A segment of length L has a leading point a and a trailing point b. When a moves along the straight
// line to a' = a + q u (|u| = 1), the trailing point moves along the segment with speed (da/dt . t),
// t = (a - b) / L: the minimum-displacement motion that keeps the length ([B] §2.1, ref. [20]).
// This integrates in closed form: with alpha the angle between u and a - b,
//   tan(alpha'/2) = tan(alpha/2) exp(-q / L),   b' = a' - L (cos alpha' u + sin alpha' w),
// w the unit vector of the part of a - b orthogonal to u. The classical tractrix (alpha = 90°) is
// x = q - L tanh(q/L), y = L sech(q/L). The motion is planar (in the plane of u and a - b), so the
// formula holds for any 3D displacement; the trailing point's displacement never exceeds q.
//
// Degenerate cases are exact: q = 0 leaves b where it is; alpha = 0 (moving away along the segment)
// and alpha = pi (moving straight back over it) translate the segment by q u. alpha = pi is an
// unstable equilibrium of the motion: any sideways component, however small, grows.

#include <string>

#include "rope/common/types.h"

namespace rope {

// Positions the tractrix functions accept: finite and within +-1e100 m, so that differences and
// their squares cannot overflow (an overflow would be a floating-point exception, not a result).
constexpr double kMaxTractrixCoordinate = 1e100;

// Throws InvalidArgument(parameter, value) unless value is finite and |value| <= kMaxTractrixCoordinate.
void requireTractrixCoordinate(const std::string& parameter, double value);

// Hot path for chains: length > 0 and leading != trailing are the caller's guarantee (unchecked).
// The returned point is exactly `length` (to rounding) from newLeading, whatever |leading - trailing|
// is, so a chain that passes its rest lengths never drifts. Metres.
Vec3 tractrixMoveTrailing(const Vec3& leading, const Vec3& trailing, const Vec3& newLeading, double length);

// Validating form: L = |leading - trailing|. Throws InvalidArgument for a coordinate that is not
// finite or beyond kMaxTractrixCoordinate ("leading[c]", "trailing[c]", "newLeading[c]") or a
// zero-length segment ("trailing").
Vec3 tractrixTrailingPoint(const Vec3& leading, const Vec3& trailing, const Vec3& newLeading);

}  // namespace rope
