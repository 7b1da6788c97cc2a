// SPDX-License-Identifier: MIT
#include "rope/rod/adaptivity.h"

#include <algorithm>

#include "rope/spline/control_polygon.h"
#include "rope/spline/knot_insertion.h"

namespace rope {

double grevilleAbscissa(const KnotVector& knots, int i) {
  const int d = knots.degree();
  double sum = 0.0;
  for (int k = 1; k <= d; ++k) sum += knots[i + k];
  return sum / d;
}

void bendMeasures(const PointList& points, std::vector<double>& bend) {
  const int n = static_cast<int>(points.size());
  bend.assign(points.size(), 0.0);
  for (int i = 1; i + 1 < n; ++i) bend[static_cast<size_t>(i)] = bendMeasure(points, i);
}

void curvatureInsertionSpans(const KnotVector& knots, const std::vector<double>& bend,
                             double insertThreshold, std::vector<int>& spans) {
  spans.clear();
  const int n = static_cast<int>(bend.size());
  double left = grevilleAbscissa(knots, 0);
  for (int i = 0; i + 1 < n; ++i) {
    const double right = grevilleAbscissa(knots, i + 1);
    if (bend[static_cast<size_t>(i)] > insertThreshold || bend[static_cast<size_t>(i + 1)] > insertThreshold) {
      const int k = knots.findSpanUnchecked(0.5 * (left + right));
      if (spans.empty() || spans.back() != k) spans.push_back(k);
    }
    left = right;
  }
}

LocalRemoval localRemoval(const KnotRemoval& plan, const PointList& values) {
  const int size = static_cast<int>(values.size());
  const int lo = std::max(0, plan.span - plan.degree - 2);
  const int hi = std::min(size - 1, plan.span + 3);
  KnotRemoval shifted = plan;
  shifted.span -= lo;
  LocalRemoval result;
  result.offset = lo;
  result.after.assign(values.begin() + lo, values.begin() + hi + 1);
  shifted.apply(result.after);
  // Insert the knot again into the shifted window: same span and alphas as the removal (both refer to
  // the knot vector after removal).
  KnotInsertion again;
  again.parameter = plan.parameter;
  again.span = shifted.span;
  again.degree = plan.degree;
  again.alpha = plan.alpha;
  LocalRemoval::Window restored = result.after;
  again.apply(restored);
  double error = 0.0;
  result.change.resize(restored.size());
  for (size_t i = 0; i < restored.size(); ++i) {
    result.change[i] = restored[i] - values[static_cast<size_t>(lo) + i];
    error = std::max(error, result.change[i].norm());
  }
  result.error = error;
  return result;
}

double RemovalMechanics::worst() const { return std::max(velocity, curvature); }

RemovalMechanics removalMechanics(const RodIntegrals& integrals, const PointList& points,
                                  const PointList& velocities, const LocalRemoval& pointRemoval,
                                  const LocalRemoval& velocityRemoval, const MechanicsBounds& bounds) {
  const int d = integrals.degree();
  const int local = d + 1;
  // Both removals use the same plan, hence the same window of changed indices.
  const int lo = pointRemoval.offset;
  const int hi = lo + static_cast<int>(pointRemoval.change.size()) - 1;
  auto changeAt = [&](const LocalRemoval& removal, int i) -> Vec3 {
    return (i < lo || i > hi) ? Vec3::Zero() : removal.change[static_cast<size_t>(i - lo)];
  };
  const int firstSpan = std::max(0, lo - d);
  const int lastSpan = std::min(integrals.spanCount() - 1, hi);

  // Mass-weighted mean velocity over the region (gravity weights are the rows of M summed).
  double mass = 0.0, restLength = 0.0;
  Vec3 momentum = Vec3::Zero();
  for (int j = firstSpan; j <= lastSpan; ++j) {
    const SpanView span = integrals.span(j);
    restLength += span.restLength;
    for (int a = 0; a < local; ++a) {
      mass += span.gravity[a];
      momentum += span.gravity[a] * velocities[static_cast<size_t>(j + a)];
    }
  }
  const Vec3 mean = mass > 0.0 ? Vec3(momentum / mass) : Vec3::Zero();

  double velocityError = 0.0, velocitySize = 0.0, curvatureError = 0.0, curvatureSize = 0.0;
  double strainError = 0.0, strainSize = 0.0, tensionError = 0.0, bendRateError = 0.0, bendRateSize = 0.0;
  for (int j = firstSpan; j <= lastSpan; ++j) {
    const SpanView span = integrals.span(j);
    for (int a = 0; a < local; ++a) {
      const size_t ia = static_cast<size_t>(j + a);
      const Vec3 dva = changeAt(velocityRemoval, j + a), dqa = changeAt(pointRemoval, j + a);
      const Vec3 va = velocities[ia] - mean;
      for (int b = 0; b < local; ++b) {
        const size_t ib = static_cast<size_t>(j + b);
        const double m = span.mass[a * local + b], g = span.curvature[a * local + b];
        velocityError += m * dva.dot(changeAt(velocityRemoval, j + b));
        velocitySize += m * va.dot(velocities[ib] - mean);
        curvatureError += g * dqa.dot(changeAt(pointRemoval, j + b));
        bendRateError += g * dva.dot(changeAt(velocityRemoval, j + b));
        bendRateSize += g * velocities[ia].dot(velocities[ib]);
        curvatureSize += g * points[ia].dot(points[ib]);
      }
    }
    for (int g = 0; g < span.gaussCount; ++g) {
      const double* db = span.dBasis + g * local;
      Vec3 tangent = Vec3::Zero(), change = Vec3::Zero();
      for (int a = 0; a < local; ++a) {
        tangent += db[a] * points[static_cast<size_t>(j + a)];
        change += db[a] * changeAt(pointRemoval, j + a);
      }
      const double inverseMetric2 = span.w1[g] / span.w0[g];  // 1 / l0'^2
      // Green–Lagrange strain (gamma^2 - 1) / 2 of method eq. 13, before and after.
      const double before = 0.5 * (tangent.squaredNorm() * inverseMetric2 - 1.0);
      const double after = 0.5 * ((tangent + change).squaredNorm() * inverseMetric2 - 1.0);
      strainError += span.w0[g] * (after - before) * (after - before);
      strainSize += span.w0[g] * before * before;
      // Geometric stiffness: under tension T = EA e a change of the tangent's direction costs
      // T |dC'_perp|^2 (the stiffness of a taut string, which has no bending stiffness at all). Only
      // the part across the tangent: a change along it re-spaces the parameter on a straight stretch
      // and is a change of strain (measured above), which the rope relaxes in a few steps.
      const double tangentNorm2 = tangent.squaredNorm();
      const Vec3 across = tangentNorm2 > 0.0 ? Vec3(change - (change.dot(tangent) / tangentNorm2) * tangent) : change;
      tensionError += bounds.axialStiffness * std::max(before, 0.0) * span.w1[g] * across.squaredNorm();
    }
  }
  // Floors (RodSettings::removalRelativeError) in the same squared norms: a field of RMS size f over
  // the region has norm^2 ~ f^2 * (mass or rest length).
  const double l = std::max(restLength, 1e-300);
  const double velocityFloor = bounds.velocityFloor * std::sqrt(mass);
  const double strainFloor = bounds.positionFloor / l * std::sqrt(l);
  const double curvatureFloor = bounds.positionFloor / (l * l) * std::sqrt(l);
  auto ratioWith = [&](double relative, double error2, double size2, double floor) {
    if (!(error2 > 0.0)) return 0.0;  // nothing changes (also 0 / 0 for a rope without bending stiffness)
    return std::sqrt(error2) / (relative * std::sqrt(std::max(size2, 0.0)) + floor);
  };
  auto ratio = [&](double error2, double size2, double floor) {
    return ratioWith(bounds.relative, error2, size2, floor);
  };
  RemovalMechanics result;
  // The velocity field in the mass norm and, more strictly, in the curvature norm (its second
  // derivative, blind to translation and rotation): a vibration mode's stiffness lives in the
  // derivatives, and the L2 norm alone let a hanging rope lose knots its modes needed (measured:
  // second and third modes 0.5-0.7 % slow).
  result.velocity = std::max(ratio(velocityError, velocitySize, velocityFloor),
                             ratio(bendRateError, bendRateSize, velocityFloor / (l * l) * std::sqrt(l)));
  // Shape: the energy of the change in bending (EI dq^T G dq) and in the tension's geometric
  // stiffness, against the internal energy there, bending and stretching (EA sum w0 e^2): a removal
  // may change the curvature of a taut, tension-dominated rope more than that of a bent cantilever,
  // whose internal energy is all bending.
  const double ea = bounds.axialStiffness, ei = integrals.bendingStiffness();
  result.curvature = ratio(ei * curvatureError + tensionError, ei * curvatureSize + ea * strainSize,
                           std::sqrt(ei) * curvatureFloor);
  // Strain is not bounded relative to itself: a removal changes a stiff rope's tiny strain (a
  // cantilever's 1e-5) by as much through a micrometre of length, a transient that the next steps
  // relax (the tension is set by the loads, and a uniform strain is exact on any knots), so only
  // the position bound applies to it. Reported for diagnostics.
  result.strain = ratio(strainError, strainSize, strainFloor);
  return result;
}

}  // namespace rope
