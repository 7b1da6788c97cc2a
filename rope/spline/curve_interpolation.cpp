// SPDX-License-Identifier: MIT
#include "rope/spline/curve_interpolation.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "rope/common/error.h"
#include "rope/spline/bspline_basis.h"
#include "rope/spline/point_validation.h"

namespace rope {
namespace {

// Square matrix with entries only on diagonals -p..p, row-major per row: entry (r, c) at
// r * (2p+1) + (c - r + p).
class BandMatrix {
 public:
  BandMatrix(int size, int halfBandwidth)
      : size_(size), p_(halfBandwidth), entries_(static_cast<size_t>(size * (2 * halfBandwidth + 1)), 0.0) {}
  bool inBand(int r, int c) const { return c - r >= -p_ && c - r <= p_ && c >= 0 && c < size_; }
  double& at(int r, int c) { return entries_[static_cast<size_t>(r * (2 * p_ + 1) + (c - r + p_))]; }

  // Gaussian elimination without pivoting, which is stable for the totally positive collocation
  // matrix of B-splines at Schoenberg–Whitney parameters (de Boor & Pinkus 1977). O(size p^2).
  void solve(PointList& rhs) {
    for (int k = 0; k < size_; ++k) {
      const double pivot = at(k, k);
      if (!(std::fabs(pivot) > 1e-300)) {
        throw NumericalFailure("interpolation matrix is singular at row " + std::to_string(k));
      }
      const int lastRow = std::min(size_ - 1, k + p_);
      for (int r = k + 1; r <= lastRow; ++r) {
        const double factor = at(r, k) / pivot;
        if (factor == 0.0) continue;
        for (int c = k; c <= lastRow; ++c) at(r, c) -= factor * at(k, c);
        rhs[static_cast<size_t>(r)] -= factor * rhs[static_cast<size_t>(k)];
      }
    }
    for (int k = size_ - 1; k >= 0; --k) {
      Vec3 value = rhs[static_cast<size_t>(k)];
      const int lastColumn = std::min(size_ - 1, k + p_);
      for (int c = k + 1; c <= lastColumn; ++c) value -= at(k, c) * rhs[static_cast<size_t>(c)];
      rhs[static_cast<size_t>(k)] = value / at(k, k);
    }
  }

 private:
  int size_;
  int p_;
  std::vector<double> entries_;
};

}  // namespace

Interpolation interpolatePolyline(const PointList& points, int degree, Parametrization parametrization) {
  if (parametrization != Parametrization::kChordLength && parametrization != Parametrization::kCentripetal) {
    throw InvalidArgument("parametrization", std::to_string(static_cast<int>(parametrization)),
                          "is not a Parametrization");
  }
  if (degree < 1 || degree > kMaxDegree) {
    throw InvalidArgument("degree", std::to_string(degree), "must be in 1.." + std::to_string(kMaxDegree));
  }
  const int count = static_cast<int>(points.size());
  if (count < degree + 1) {
    throw InvalidArgument("points.size()", std::to_string(count),
                          "must be >= degree+1 = " + std::to_string(degree + 1));
  }
  requireFinitePoints("points", points);
  // Chord lengths; a repeated point has no parameter interval and makes the system singular.
  std::vector<double> chord(static_cast<size_t>(count), 0.0);
  double total = 0.0;
  for (int i = 1; i < count; ++i) {
    const double length = (points[static_cast<size_t>(i)] - points[static_cast<size_t>(i - 1)]).norm();
    if (!(length > 0.0)) {
      throw InvalidArgument("points[" + std::to_string(i) + "]", "coincides with points[" + std::to_string(i - 1) + "]",
                            "consecutive points must be distinct");
    }
    if (!std::isfinite(length)) {
      throw InvalidArgument("points[" + std::to_string(i) + "]", formatValue(length),
                            "distance to the previous point overflows");
    }
    chord[static_cast<size_t>(i)] = length;
    total += length;
  }
  // Piegl & Tiller eq. 9.5 (chord) / 9.6 (centripetal), scaled to [0, total chord length] so that s
  // approximates arc length in metres.
  std::vector<double> parameters(static_cast<size_t>(count), 0.0);
  {
    double sum = 0.0;
    double weights = 0.0;
    for (int i = 1; i < count; ++i) {
      weights += parametrization == Parametrization::kCentripetal ? std::sqrt(chord[static_cast<size_t>(i)])
                                                                  : chord[static_cast<size_t>(i)];
    }
    for (int i = 1; i < count - 1; ++i) {
      sum += parametrization == Parametrization::kCentripetal ? std::sqrt(chord[static_cast<size_t>(i)])
                                                              : chord[static_cast<size_t>(i)];
      parameters[static_cast<size_t>(i)] = total * (sum / weights);
    }
    parameters.back() = total;
  }
  // Piegl & Tiller eq. 9.8: clamped ends, interior knots by averaging degree consecutive parameters.
  const int p = degree;
  std::vector<double> knots(static_cast<size_t>(count + p + 1), 0.0);
  for (int i = 0; i <= p; ++i) knots[static_cast<size_t>(count + i)] = total;
  for (int j = 1; j <= count - 1 - p; ++j) {
    double sum = 0.0;
    for (int i = j; i <= j + p - 1; ++i) sum += parameters[static_cast<size_t>(i)];
    knots[static_cast<size_t>(j + p)] = sum / p;
  }
  KnotVector knotVector(p, std::move(knots));

  // Collocation system N_i(s_k) P_i = Q_k, banded with half bandwidth p.
  BandMatrix matrix(count, p);
  BasisValues basis;
  for (int k = 0; k < count; ++k) {
    const double s = parameters[static_cast<size_t>(k)];
    evaluateBasis(knotVector, knotVector.findSpanUnchecked(s), s, 0, basis);
    for (int j = 0; j <= p; ++j) {
      const int column = basis.firstIndex() + j;
      const double value = basis.d[0][static_cast<size_t>(j)];
      if (value == 0.0) continue;
      if (!matrix.inBand(k, column)) {
        throw NumericalFailure("interpolation matrix entry (" + std::to_string(k) + ", " + std::to_string(column) +
                               ") outside the expected band");
      }
      matrix.at(k, column) = value;
    }
  }
  PointList controlPoints = points;
  matrix.solve(controlPoints);
  for (const Vec3& q : controlPoints) {
    if (!q.allFinite()) throw NumericalFailure("interpolation produced a non-finite control point");
  }
  return Interpolation{BSplineCurve(std::move(knotVector), std::move(controlPoints)), std::move(parameters)};
}

}  // namespace rope
