// SPDX-License-Identifier: MIT
#pragma once
// Measures on the control polygon used by adaptivity ([A] eq. 13, [B] §3; docs/method.md §10).

#include <cstddef>

#include "rope/common/types.h"

namespace rope {

// [A] eq. 13 with the sign the extracted text lost: c_i = (1 - a.b / (|a||b|)) / 2 with
// a = q_i - q_{i-1}, b = q_{i+1} - q_i. Range [0, 1]: 0 straight, 1 folded back. Defined for
// 1 <= i <= n-2 ("i"); a zero-length side has no direction to bend and gives 0.
double bendMeasure(const PointList& points, int i);
// The same on the polygon points[0 .. count-1] (a window of a larger one, held anywhere).
double bendMeasure(const Vec3* points, std::size_t count, int i);

// Included angle theta_i in [0, pi] between the sides at q_i ([B]): pi is straight. Same domain and
// zero-length convention as bendMeasure (gives pi). c_i = (1 + cos theta_i) / 2.
double includedAngle(const PointList& points, int i);

double bendMeasureFromAngle(double includedAngleRadians);
double angleFromBendMeasure(double bendMeasure);

// Sum of the side lengths of the polygon (metres).
double polygonLength(const PointList& points);

}  // namespace rope
