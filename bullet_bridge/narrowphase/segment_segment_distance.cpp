// SPDX-License-Identifier: MIT
#include "bullet_bridge/narrowphase/segment_segment_distance.h"

#include <algorithm>
#include <cmath>

namespace rope::bullet {

namespace {

double clamp01(double x) { return std::min(1.0, std::max(0.0, x)); }

}  // namespace

SegmentPairClosest segmentSegmentClosest(const btVector3& p0, const btVector3& p1, const btVector3& q0,
                                         const btVector3& q1) {
  // In double whatever btScalar is: the parallel test below divides small differences.
  const double d1[3] = {double(p1.x() - p0.x()), double(p1.y() - p0.y()), double(p1.z() - p0.z())};
  const double d2[3] = {double(q1.x() - q0.x()), double(q1.y() - q0.y()), double(q1.z() - q0.z())};
  const double r[3] = {double(p0.x() - q0.x()), double(p0.y() - q0.y()), double(p0.z() - q0.z())};
  const auto dot = [](const double* u, const double* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  const double lengthScale2 = std::max(a, e);
  double s = 0.0, t = 0.0;
  if (!(lengthScale2 > 0.0)) {
    // Both segments are points.
  } else if (!(a > 1e-24 * lengthScale2)) {
    t = clamp01(f / e);  // first segment is a point
  } else {
    const double c = dot(d1, r);
    if (!(e > 1e-24 * lengthScale2)) {
      s = clamp01(-c / a);  // second segment is a point
    } else {
      const double b = dot(d1, d2);
      const double denominator = a * e - b * b;  // |d1 x d2|^2 >= 0
      if (denominator > 1e-12 * a * e) {
        // Minimise over s with t free, clamp, then re-solve t and re-clamp s (Ericson, RTCD 5.1.9).
        s = clamp01((b * f - c * e) / denominator);
        t = (b * s + f) / e;
        if (t < 0.0) {
          t = 0.0;
          s = clamp01(-c / a);
        } else if (t > 1.0) {
          t = 1.0;
          s = clamp01((b - c) / a);
        }
      } else {
        // Parallel: project the second segment's ends onto the first and take the middle of the
        // overlap of [0, 1] with their range; if they do not overlap, the nearer ends.
        const double sq0 = -c / a;           // q0 on the first line
        const double sq1 = (b - c) / a;      // q1 on the first line
        const double lo = std::max(0.0, std::min(sq0, sq1));
        const double hi = std::min(1.0, std::max(sq0, sq1));
        s = lo <= hi ? 0.5 * (lo + hi) : (std::min(sq0, sq1) > 1.0 ? 1.0 : 0.0);
        t = clamp01((b * s + f) / e);
        s = clamp01((b * t - c) / a);
      }
    }
  }
  double gap[3];
  for (int i = 0; i < 3; ++i) gap[i] = r[i] + s * d1[i] - t * d2[i];
  SegmentPairClosest result;
  result.s = s;
  result.t = t;
  result.distance = std::sqrt(dot(gap, gap));
  return result;
}

}  // namespace rope::bullet
