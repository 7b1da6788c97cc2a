// SPDX-License-Identifier: MIT
#pragma once
// Global interpolation of a polyline by a clamped B-spline (Piegl & Tiller A9.1), used to lay a rope
// along a path ([B] step 1). Parameters are assigned by chord length (or centripetal) and scaled to
// [0, total chord length], so that s is close to arc length in metres; interior knots by averaging.

#include <vector>

#include "rope/common/types.h"
#include "rope/spline/bspline_curve.h"

namespace rope {

enum class Parametrization { kChordLength, kCentripetal };

struct Interpolation {
  BSplineCurve curve;
  std::vector<double> parameters;  // s at which the curve passes through each input point
};

// Throws InvalidArgument: "degree" outside 1..kMaxDegree, "points.size()" < degree+1,
// "points[i]" non-finite or coinciding with points[i-1], "parametrization" not a Parametrization.
Interpolation interpolatePolyline(const PointList& points, int degree = 3,
                                  Parametrization parametrization = Parametrization::kChordLength);

}  // namespace rope
