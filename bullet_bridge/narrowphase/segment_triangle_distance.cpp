// SPDX-License-Identifier: MIT
#include "bullet_bridge/narrowphase/segment_triangle_distance.h"

#include <algorithm>
#include <cmath>

namespace rope::bullet {

namespace {

btScalar clamp01(btScalar x) { return std::min(btScalar(1), std::max(btScalar(0), x)); }

// Closest point of segment (a, b) to p as the weight of b.
btScalar closestOnSegmentParameter(const btVector3& p, const btVector3& a, const btVector3& b) {
  const btVector3 ab = b - a;
  const btScalar length2 = ab.length2();
  if (!(length2 > 0)) return 0;
  return clamp01((p - a).dot(ab) / length2);
}

}  // namespace

void closestPointOnTriangle(const btVector3& p, const btVector3& a, const btVector3& b,
                            const btVector3& c, btScalar weights[3]) {
  // Voronoi-region walk: vertex regions, then edge regions, then the face.
  const btVector3 ab = b - a;
  const btVector3 ac = c - a;
  const btVector3 ap = p - a;
  const btScalar d1 = ab.dot(ap);
  const btScalar d2 = ac.dot(ap);
  auto set = [weights](btScalar wa, btScalar wb, btScalar wc) {
    weights[0] = wa;
    weights[1] = wb;
    weights[2] = wc;
  };
  if (d1 <= 0 && d2 <= 0) return set(1, 0, 0);
  const btVector3 bp = p - b;
  const btScalar d3 = ab.dot(bp);
  const btScalar d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return set(0, 1, 0);
  const btVector3 cp = p - c;
  const btScalar d5 = ab.dot(cp);
  const btScalar d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return set(0, 0, 1);
  const btScalar vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0) {
    const btScalar v = d1 / (d1 - d3);
    return set(1 - v, v, 0);
  }
  const btScalar vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0) {
    const btScalar w = d2 / (d2 - d6);
    return set(1 - w, 0, w);
  }
  const btScalar va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0 && (d4 - d3) + (d5 - d6) > 0) {
    const btScalar w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return set(0, 1 - w, w);
  }
  const btScalar sum = va + vb + vc;  // = |ab x ac|^2 up to rounding
  if (sum > 0 && va >= 0 && vb >= 0 && vc >= 0) {
    return set(va / sum, vb / sum, vc / sum);
  }
  // Collinear vertices (or rounding at a near-degenerate triangle): the nearest of the edges.
  const btVector3* const vertices[3] = {&a, &b, &c};
  btScalar best = -1;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const btScalar u = closestOnSegmentParameter(p, *vertices[i], *vertices[j]);
    const btScalar d2Edge = (p - (*vertices[i] + (*vertices[j] - *vertices[i]) * u)).length2();
    if (best < 0 || d2Edge < best) {
      best = d2Edge;
      btScalar w[3] = {0, 0, 0};
      w[i] = 1 - u;
      w[j] = u;
      set(w[0], w[1], w[2]);
    }
  }
}

void closestSegmentSegment(const btVector3& p1, const btVector3& q1, const btVector3& p2,
                           const btVector3& q2, btScalar& s, btScalar& t) {
  const btVector3 d1 = q1 - p1;
  const btVector3 d2 = q2 - p2;
  const btVector3 r = p1 - p2;
  const btScalar a = d1.length2();
  const btScalar e = d2.length2();
  const btScalar f = d2.dot(r);
  if (!(a > 0) && !(e > 0)) {
    s = t = 0;
    return;
  }
  if (!(a > 0)) {
    s = 0;
    t = clamp01(f / e);
    return;
  }
  const btScalar c = d1.dot(r);
  if (!(e > 0)) {
    t = 0;
    s = clamp01(-c / a);
    return;
  }
  const btScalar b = d1.dot(d2);
  const btScalar denom = a * e - b * b;  // >= 0; 0 for parallel segments
  // Parallel segments: any s works, take 0 and let the clamping below pick the matching t.
  s = denom > 0 ? clamp01((b * f - c * e) / denom) : btScalar(0);
  t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = clamp01(-c / a);
  } else if (t > 1) {
    t = 1;
    s = clamp01((b - c) / a);
  }
}

SegmentTriangleClosest segmentTriangleClosest(const btVector3& p, const btVector3& q,
                                              const btVector3& a, const btVector3& b,
                                              const btVector3& c) {
  SegmentTriangleClosest best;
  const btVector3 n = (b - a).cross(c - a);
  if (n.length2() > 0) {
    const btScalar hp = n.dot(p - a);
    const btScalar hq = n.dot(q - a);
    if ((hp < 0 && hq > 0) || (hp > 0 && hq < 0)) {
      const btScalar s = hp / (hp - hq);
      const btVector3 x = p + (q - p) * s;
      btScalar w[3];
      closestPointOnTriangle(x, a, b, c, w);
      const btVector3 onTriangle = a * w[0] + b * w[1] + c * w[2];
      // Inside the triangle (the closest point is x itself, up to rounding of the projection).
      if (w[0] > 0 && w[1] > 0 && w[2] > 0) {
        best.distance = 0;
        best.s = s;
        best.pointOnSegment = x;
        best.pointOnTriangle = onTriangle;
        best.crossesPlane = true;
        return best;
      }
    }
  }

  btScalar bestDistance2 = -1;
  auto consider = [&](btScalar s, const btVector3& onSegment, const btVector3& onTriangle) {
    const btScalar d2 = (onSegment - onTriangle).length2();
    if (bestDistance2 < 0 || d2 < bestDistance2) {
      bestDistance2 = d2;
      best.s = s;
      best.pointOnSegment = onSegment;
      best.pointOnTriangle = onTriangle;
    }
  };
  btScalar w[3];
  closestPointOnTriangle(p, a, b, c, w);
  consider(0, p, a * w[0] + b * w[1] + c * w[2]);
  closestPointOnTriangle(q, a, b, c, w);
  consider(1, q, a * w[0] + b * w[1] + c * w[2]);
  const btVector3* const vertices[3] = {&a, &b, &c};
  for (int i = 0; i < 3; ++i) {
    const btVector3& e0 = *vertices[i];
    const btVector3& e1 = *vertices[(i + 1) % 3];
    btScalar s, t;
    closestSegmentSegment(p, q, e0, e1, s, t);
    consider(s, p + (q - p) * s, e0 + (e1 - e0) * t);
  }
  best.distance = std::sqrt(bestDistance2);
  return best;
}

}  // namespace rope::bullet
