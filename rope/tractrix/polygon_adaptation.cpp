// SPDX-License-Identifier: MIT
#include "rope/tractrix/polygon_adaptation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "rope/spline/knot_insertion.h"

namespace rope {
namespace {

// Included angle at interior vertex i in [0, pi] (pi = straight), as control_polygon.h's
// includedAngle() defines it, without its per-call validation: the points here are the rope's own
// finite state. atan2 keeps full accuracy near straight, where the thresholds live.
double cornerAngle(const PointList& points, int i) {
  const Vec3 a = points[static_cast<size_t>(i)] - points[static_cast<size_t>(i - 1)];
  const Vec3 b = points[static_cast<size_t>(i + 1)] - points[static_cast<size_t>(i)];
  return std::atan2(a.cross(b).norm(), -a.dot(b));
}

// Smallest included angle among the interior corners first..last (clipped to 1..n-2); pi if none.
double smallestAngle(const PointList& points, int first, int last) {
  const int n = static_cast<int>(points.size());
  double smallest = std::acos(-1.0);
  for (int i = std::max(1, first); i <= std::min(n - 2, last); ++i) smallest = std::min(smallest, cornerAngle(points, i));
  return smallest;
}

}  // namespace

int subdivideSharpCorners(KnotVector& knots, PointList& points, double subdivisionAngle, double minSide,
                          int maxControlPoints) {
  const int d = knots.degree();
  int insertions = 0;
  std::vector<double> angles;
  std::vector<int> sharp;
  PointList candidate;
  while (static_cast<int>(points.size()) < maxControlPoints) {
    const int n = static_cast<int>(points.size());
    angles.assign(static_cast<size_t>(n), std::acos(-1.0));
    sharp.clear();
    for (int i = 1; i <= n - 2; ++i) {
      angles[static_cast<size_t>(i)] = cornerAngle(points, i);
      if (angles[static_cast<size_t>(i)] < subdivisionAngle) sharp.push_back(i);
    }
    // Sharpest first; a corner that cannot be cut (its spans are too short to split without a side
    // below minSide) gives way to the next one.
    std::sort(sharp.begin(), sharp.end(),
              [&](int x, int y) { return angles[static_cast<size_t>(x)] < angles[static_cast<size_t>(y)]; });
    bool inserted = false;
    for (const int corner : sharp) {
      // Inserting into span k replaces the corners q_{k-d+1} .. q_{k-1} by d points on their sides
      // (Boehm, method eq. 4), so the corner is cut by the spans k = corner+1 .. corner+d-1 inside d .. n-1.
      // Of those, take the one whose cut corners are the most bent on average: it opens the most.
      int bestSpan = -1;
      double bestScore = std::numeric_limits<double>::infinity();
      for (int k = std::max(d, corner + 1); k <= std::min(n - 1, corner + d - 1); ++k) {
        const double mid = 0.5 * (knots[k] + knots[k + 1]);
        if (!(mid > knots[k] && mid < knots[k + 1])) continue;  // span too short to split
        const int first = std::max(1, k - d + 1);
        const int last = std::min(n - 2, k - 1);
        double score = 0.0;
        for (int i = first; i <= last; ++i) score += angles[static_cast<size_t>(i)];
        score /= (last - first + 1);
        if (score < bestScore) {
          bestScore = score;
          bestSpan = k;
        }
      }
      if (bestSpan < 0) continue;
      const KnotInsertion plan = planKnotInsertion(knots, 0.5 * (knots[bestSpan] + knots[bestSpan + 1]));
      candidate = points;
      plan.apply(candidate);
      bool longEnough = true;
      for (int i = plan.firstChanged() - 1; longEnough && i <= plan.lastChanged(); ++i) {
        longEnough = (candidate[static_cast<size_t>(i + 1)] - candidate[static_cast<size_t>(i)]).norm() >= minSide;
      }
      if (!longEnough) continue;
      knots.insertValue(plan.parameter);
      points.swap(candidate);
      ++insertions;
      inserted = true;
      break;
    }
    if (!inserted) break;
  }
  return insertions;
}

int mergeStraightCorners(KnotVector& knots, PointList& points, const MergeLimits& limits,
                         std::vector<MergeRecord>& records) {
  const int d = knots.degree();
  int merges = 0;
  std::vector<double> rejected;  // knot values whose merge the limits refused in this call
  PointList candidate;
  while (static_cast<int>(points.size()) > limits.minControlPoints) {
    const int n = static_cast<int>(points.size());
    // Removing the knot at index r replaces q_{r-d} .. q_{r-1} (knot_removal.h); rank the interior
    // knots by the smallest angle among those corners, straightest first.
    int bestIndex = -1;
    double bestAngle = limits.mergingAngle;
    for (int r = d + 1; r <= n - 1; ++r) {
      if (knots[r] == knots[r + 1] || knots[r] == knots[r - 1]) continue;  // only simple knots
      if (std::find(rejected.begin(), rejected.end(), knots[r]) != rejected.end()) continue;
      const double straightness = smallestAngle(points, r - d, r - 1);
      if (straightness > bestAngle) {
        bestAngle = straightness;
        bestIndex = r;
      }
    }
    if (bestIndex < 0) break;
    const double s = knots[bestIndex];
    // The core plans both sweeps and picks the one with the smaller length error ([B] §3.2).
    const KnotRemoval plan = planKnotRemoval(knots, points, s);
    candidate = points;
    plan.apply(candidate);
    // After removal the new points sit at r-d .. r-2; their corners, both neighbours and the sides
    // between them changed.
    bool accept = plan.chosenShapeError() <= limits.maxShapeError;
    const int last = std::min(static_cast<int>(candidate.size()) - 2, plan.knotIndex - 1);
    for (int i = std::max(0, plan.knotIndex - d - 1); accept && i <= last; ++i) {
      accept = (candidate[static_cast<size_t>(i + 1)] - candidate[static_cast<size_t>(i)]).norm() >= limits.minSide;
    }
    if (accept && limits.guardAngle > 0.0) {
      accept = smallestAngle(candidate, plan.knotIndex - d - 1, plan.knotIndex - 1) >= limits.guardAngle;
    }
    if (!accept) {
      rejected.push_back(s);
      continue;
    }
    knots.eraseAt(plan.knotIndex);
    points.swap(candidate);
    MergeRecord record;
    record.parameter = s;
    record.chosen = plan.chosen;
    record.lengthError = plan.lengthError;
    record.shapeError = plan.shapeError;
    records.push_back(record);
    ++merges;
  }
  return merges;
}

}  // namespace rope
