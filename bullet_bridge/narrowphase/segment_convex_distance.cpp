// SPDX-License-Identifier: MIT
#include "bullet_bridge/narrowphase/segment_convex_distance.h"

#include <algorithm>
#include <cmath>

#include "bullet_bridge/narrowphase/segment_triangle_distance.h"

namespace rope::bullet {

namespace {

// Relative gap between GJK's upper bound |v| and its lower bound v.w/|v| at which it stops.
constexpr btScalar kRelativeTolerance = 1e-12;
constexpr int kMaxIterations = 96;

// A vertex of the Minkowski difference core - segment: w = onCore - segmentPoint(t).
struct Vertex {
  btVector3 w;
  btVector3 onCore;
  btScalar t;
};

struct Simplex {
  Vertex vertex[4];
  btScalar weight[4];
  int size = 0;

  // Keeps the vertices with positive weight (the supporting face of the closest point).
  void compact() {
    int kept = 0;
    for (int i = 0; i < size; ++i) {
      if (weight[i] > 0) {
        vertex[kept] = vertex[i];
        weight[kept] = weight[i];
        ++kept;
      }
    }
    size = kept;
  }

  btVector3 point() const {
    btVector3 v(0, 0, 0);
    for (int i = 0; i < size; ++i) v += vertex[i].w * weight[i];
    return v;
  }
};

void solveSegment(Simplex& s) {
  const btVector3& a = s.vertex[0].w;
  const btVector3 ab = s.vertex[1].w - a;
  const btScalar length2 = ab.length2();
  btScalar u = length2 > 0 ? -a.dot(ab) / length2 : btScalar(0);
  u = std::min(btScalar(1), std::max(btScalar(0), u));
  s.weight[0] = 1 - u;
  s.weight[1] = u;
}

void solveTriangle(Simplex& s) {
  closestPointOnTriangle(btVector3(0, 0, 0), s.vertex[0].w, s.vertex[1].w, s.vertex[2].w,
                         s.weight);
}

// Returns false if the origin lies inside the (non-degenerate) tetrahedron.
bool solveTetrahedron(Simplex& s, btScalar scale) {
  const btVector3 a = s.vertex[0].w;
  const btVector3 b = s.vertex[1].w;
  const btVector3 c = s.vertex[2].w;
  const btVector3 d = s.vertex[3].w;
  const btScalar volume6 = (b - a).cross(c - a).dot(d - a);
  const bool degenerate = std::fabs(volume6) <= 1e-14 * scale * scale * scale;
  // Faces as vertex triples, each with its opposite vertex.
  static const int kFaces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
  bool outside = false;
  btScalar bestDistance2 = -1;
  btScalar bestWeight[4] = {0, 0, 0, 0};
  for (const auto& face : kFaces) {
    const btVector3& p0 = s.vertex[face[0]].w;
    const btVector3& p1 = s.vertex[face[1]].w;
    const btVector3& p2 = s.vertex[face[2]].w;
    const btVector3 normal = (p1 - p0).cross(p2 - p0);
    const btScalar originSide = -normal.dot(p0);
    const btScalar oppositeSide = normal.dot(s.vertex[face[3]].w - p0);
    if (!degenerate && originSide * oppositeSide >= 0) continue;  // origin on the inner side
    outside = true;
    btScalar w[3];
    closestPointOnTriangle(btVector3(0, 0, 0), p0, p1, p2, w);
    const btScalar distance2 = (p0 * w[0] + p1 * w[1] + p2 * w[2]).length2();
    if (bestDistance2 < 0 || distance2 < bestDistance2) {
      bestDistance2 = distance2;
      for (int i = 0; i < 4; ++i) bestWeight[i] = 0;
      for (int i = 0; i < 3; ++i) bestWeight[face[i]] = w[i];
    }
  }
  if (!outside) return false;
  for (int i = 0; i < 4; ++i) s.weight[i] = bestWeight[i];
  return true;
}

// The point of the box (half extents h about the origin) nearest to x.
btVector3 clampToBox(const btVector3& x, const btVector3& half) {
  return btVector3(std::min(half.x(), std::max(-half.x(), x.x())), std::min(half.y(), std::max(-half.y(), x.y())),
                   std::min(half.z(), std::max(-half.z(), x.z())));
}

// Sets the status of a query whose least squared distance is distance2 (and its distance unless it
// touches): false if nothing more is to be set (touching, or beyond the cutoff).
bool classify(btScalar distance2, btScalar contactTolerance2, btScalar cutoff, SegmentConvexDistance& result) {
  if (distance2 <= contactTolerance2) {
    result.status = SegmentConvexDistance::Status::Intersecting;
    return false;
  }
  result.distance = std::sqrt(distance2);
  if (result.distance > cutoff) {
    result.status = SegmentConvexDistance::Status::BeyondCutoff;
    return false;
  }
  return true;
}

// A box (half extents h about the origin) in closed form, the commonest body (floors, tables, bars):
// GJK there cost a quarter of a resting rope's step. The squared distance of p + t (q - p) from the
// box is sum_k max(0, |x_k(t)| - h_k)^2, convex and piecewise quadratic in t between the (at most six)
// parameters where a coordinate crosses a face's plane; its minimum is the least of each piece's
// clamped vertex. Same results as GJK, which terminates on the same closest features (to rounding).
SegmentConvexDistance segmentBoxDistance(const btVector3& p, const btVector3& q, const btVector3& half,
                                         btScalar cutoff, btScalar contactTolerance2) {
  const btVector3 d = q - p;
  btScalar breaks[8];
  int count = 0;
  breaks[count++] = 0;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == btScalar(0)) continue;
    for (const btScalar plane : {half[k], -half[k]}) {
      const btScalar t = (plane - p[k]) / d[k];
      if (!(t > btScalar(0) && t < btScalar(1))) continue;
      int at = count++;  // insertion into the sorted parameters (at most six)
      for (; breaks[at - 1] > t; --at) breaks[at] = breaks[at - 1];
      breaks[at] = t;
    }
  }
  breaks[count++] = 1;
  btScalar bestT = 0, best2 = std::numeric_limits<btScalar>::infinity();
  for (int i = 0; i + 1 < count; ++i) {
    const btScalar a = breaks[i], b = breaks[i + 1];
    const btScalar middle = btScalar(0.5) * (a + b);
    // On this piece each coordinate stays above, inside or below its slab: f = A t^2 + 2 B t + C.
    btScalar A = 0, B = 0;
    for (int k = 0; k < 3; ++k) {
      const btScalar x = p[k] + middle * d[k];
      if (x > half[k] || x < -half[k]) {
        const btScalar face = x > half[k] ? half[k] : -half[k];
        A += d[k] * d[k];
        B += d[k] * (p[k] - face);
      }
    }
    const btScalar t = A > btScalar(0) ? std::min(b, std::max(a, -B / A)) : a;
    const btVector3 x = p + d * t;
    const btScalar distance2 = (x - clampToBox(x, half)).length2();
    if (distance2 < best2) {
      best2 = distance2;
      bestT = t;
    }
  }
  SegmentConvexDistance result;
  if (!classify(best2, contactTolerance2, cutoff, result)) return result;
  result.t = bestT;
  result.pointOnSegment = p + d * bestT;
  result.pointOnCore = clampToBox(result.pointOnSegment, half);
  return result;
}

}  // namespace

SegmentConvexDistance segmentConvexDistance(const btVector3& p, const btVector3& q,
                                            const ConvexCore& core, btScalar cutoff) {
  SegmentConvexDistance result;
  const btScalar scale = std::max({btScalar(1e-3), core.size, p.length(), q.length()});
  // Below this the closest points carry no usable direction: treat as touching the core.
  const btScalar contactTolerance2 = (1e-12 * scale) * (1e-12 * scale);
  if (core.kind == ConvexCore::Kind::Box) return segmentBoxDistance(p, q, core.halfExtents, cutoff, contactTolerance2);
  const btVector3 axis = q - p;

  auto support = [&](const btVector3& direction) {
    // Support of core - segment in `direction`: core's farthest point minus the segment's nearest.
    Vertex v;
    v.onCore = core.support(direction);
    v.t = axis.dot(direction) > 0 ? btScalar(0) : btScalar(1);
    v.w = v.onCore - (v.t > 0 ? q : p);
    return v;
  };

  Simplex simplex;
  simplex.vertex[0] = support(p + axis * btScalar(0.5) - core.interiorPoint);
  simplex.weight[0] = 1;
  simplex.size = 1;
  btVector3 v = simplex.vertex[0].w;
  btScalar vv = v.length2();

  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    if (vv <= contactTolerance2) {
      result.status = SegmentConvexDistance::Status::Intersecting;
      return result;
    }
    const Vertex w = support(-v);
    const btScalar vw = v.dot(w.w);
    // w.v/|v| bounds the distance from below (the plane normal to v through w separates).
    if (vw > 0 && vw * vw > cutoff * cutoff * vv) {
      result.status = SegmentConvexDistance::Status::BeyondCutoff;
      return result;
    }
    if (vv - vw <= kRelativeTolerance * vv) break;
    bool repeated = false;
    for (int i = 0; i < simplex.size; ++i) {
      if ((simplex.vertex[i].w - w.w).length2() <= contactTolerance2) repeated = true;
    }
    if (repeated) break;

    Simplex next = simplex;
    next.vertex[next.size++] = w;
    switch (next.size) {
      case 2:
        solveSegment(next);
        break;
      case 3:
        solveTriangle(next);
        break;
      default:
        if (!solveTetrahedron(next, scale)) {
          result.status = SegmentConvexDistance::Status::Intersecting;
          return result;
        }
        break;
    }
    next.compact();
    const btVector3 nextV = next.point();
    const btScalar nextVV = nextV.length2();
    if (!(nextVV < vv)) break;  // no progress: rounding has taken over
    simplex = next;
    v = nextV;
    vv = nextVV;
  }

  if (!classify(vv, contactTolerance2, cutoff, result)) return result;
  btVector3 onCore(0, 0, 0);
  btScalar t = 0;
  for (int i = 0; i < simplex.size; ++i) {
    onCore += simplex.vertex[i].onCore * simplex.weight[i];
    t += simplex.vertex[i].t * simplex.weight[i];
  }
  result.t = std::min(btScalar(1), std::max(btScalar(0), t));
  result.pointOnCore = onCore;
  result.pointOnSegment = p + axis * result.t;
  return result;
}

}  // namespace rope::bullet
