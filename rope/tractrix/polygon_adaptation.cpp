#include "rope/tractrix/polygon_adaptation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rope/spline/control_polygon.h"
#include "rope/spline/knot_insertion.h"

namespace rope {
namespace {

// Included angle at interior vertex i; the clamped ends have none.
double cornerAngle(const PointList& points, int i) { return includedAngle(points, i); }

// Smallest included angle among the interior corners first..last (clipped to 1..n-2); pi if none.
double smallestAngle(const PointList& points, int first, int last) {
  const int n = static_cast<int>(points.size());
  double smallest = std::acos(-1.0);
  for (int i = std::max(1, first); i <= std::min(n - 2, last); ++i) smallest = std::min(smallest, cornerAngle(points, i));
  return smallest;
}

}  // namespace

int subdivideSharpCorners(KnotVector& knots, PointList& points, double subdivisionAngle, int maxControlPoints) {
  const int d = knots.degree();
  int insertions = 0;
  std::vector<double> angles;
  while (static_cast<int>(points.size()) < maxControlPoints) {
    const int n = static_cast<int>(points.size());
    angles.assign(static_cast<size_t>(n), std::acos(-1.0));
    int sharpest = -1;
    for (int i = 1; i <= n - 2; ++i) {
      angles[static_cast<size_t>(i)] = cornerAngle(points, i);
      if (angles[static_cast<size_t>(i)] < subdivisionAngle &&
          (sharpest < 0 || angles[static_cast<size_t>(i)] < angles[static_cast<size_t>(sharpest)])) {
        sharpest = i;
      }
    }
    if (sharpest < 0) break;
    // Inserting into span k replaces the corners q_{k-d+1} .. q_{k-1} by d points on their sides
    // (Boehm, spec §1), so corner i is cut by the spans k = i+1 .. i+d-1 inside d .. n-1.
    int bestSpan = -1;
    double bestScore = std::numeric_limits<double>::infinity();
    for (int k = std::max(d, sharpest + 1); k <= std::min(n - 1, sharpest + d - 1); ++k) {
      const double mid = 0.5 * (knots[k] + knots[k + 1]);
      if (!(mid > knots[k] && mid < knots[k + 1])) continue;  // span too short to split
      double score = 0.0;
      for (int i = std::max(1, k - d + 1); i <= std::min(n - 2, k - 1); ++i) score += angles[static_cast<size_t>(i)];
      score /= (std::min(n - 2, k - 1) - std::max(1, k - d + 1) + 1);
      if (score < bestScore) {
        bestScore = score;
        bestSpan = k;
      }
    }
    if (bestSpan < 0) break;  // the spans around the corner cannot be split any further
    insertKnot(knots, points, 0.5 * (knots[bestSpan] + knots[bestSpan + 1]));
    ++insertions;
  }
  return insertions;
}

int mergeStraightCorners(KnotVector& knots, PointList& points, double mergingAngle, double guardAngle,
                         double minSide, int minControlPoints, std::vector<MergeRecord>& records) {
  const int d = knots.degree();
  int merges = 0;
  std::vector<double> rejected;  // knot values whose merge the guard refused in this call
  PointList candidate;
  while (static_cast<int>(points.size()) > minControlPoints) {
    const int n = static_cast<int>(points.size());
    // Removing the knot at index r replaces q_{r-d} .. q_{r-1} (knot_removal.h); rank the interior
    // knots by the smallest angle among those corners, straightest first.
    int bestIndex = -1;
    double bestAngle = mergingAngle;
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
    bool accept = true;
    const int last = std::min(static_cast<int>(candidate.size()) - 2, plan.knotIndex - 1);
    for (int i = std::max(0, plan.knotIndex - d - 1); accept && i <= last; ++i) {
      accept = (candidate[static_cast<size_t>(i + 1)] - candidate[static_cast<size_t>(i)]).norm() >= minSide;
    }
    if (accept && guardAngle > 0.0) {
      accept = smallestAngle(candidate, plan.knotIndex - d - 1, plan.knotIndex - 1) >= guardAngle;
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
