// SPDX-License-Identifier: MIT
#pragma once
// Knot vector of a B-spline ([A] §3.1; docs/method.md §1): s_0 <= s_1 <= ... <= s_{n+d} for n control points of
// degree d. The curve is defined on the valid range [s_d, s_n]. Clamped (open) vectors repeat the end
// knots d+1 times so that the curve ends on its first and last control points; unclamped ones do not
// ([A]'s own example: {0, 1, ..., 14} for 11 cubic control points). Parameters are dimensionless
// unless a caller chooses otherwise (interpolation uses chord length in metres).

#include <cstddef>
#include <vector>

namespace rope {

// Degrees 1..5 are supported; fixed-size scratch arrays elsewhere are sized by this.
constexpr int kMaxDegree = 5;

class KnotVector {
 public:
  // Throws InvalidArgument naming the field: "degree" outside 1..kMaxDegree, "knots.size()" giving
  // fewer than degree+1 control points, "knots[i]" non-finite or smaller than knots[i-1], an empty
  // valid range (s_d == s_n), or a knot repeated more than degree+1 times.
  KnotVector(int degree, std::vector<double> knots);

  // Clamped uniform knots over [begin, end] (begin < end).
  static KnotVector clampedUniform(int degree, int controlPointCount, double begin = 0.0, double end = 1.0);
  // Unclamped uniform knots s_i = begin + i * spacing (spacing > 0).
  static KnotVector uniform(int degree, int controlPointCount, double begin = 0.0, double spacing = 1.0);

  int degree() const { return degree_; }
  int controlPointCount() const { return static_cast<int>(knots_.size()) - degree_ - 1; }
  int size() const { return static_cast<int>(knots_.size()); }
  double operator[](int i) const { return knots_[static_cast<std::size_t>(i)]; }
  const std::vector<double>& values() const { return knots_; }

  double validBegin() const { return knots_[static_cast<std::size_t>(degree_)]; }
  double validEnd() const { return knots_[static_cast<std::size_t>(controlPointCount())]; }
  // True for finite s in [validBegin, validEnd].
  bool contains(double s) const;
  // True if the first (last) d+1 knots are equal.
  bool isClampedBegin() const;
  bool isClampedEnd() const;

  // Span k with s_k <= s < s_{k+1} and d <= k <= n-1; s == validEnd gives the last non-empty span.
  // Throws InvalidArgument("s", ...) for NaN or s outside the valid range. O(log n).
  int findSpan(double s) const;
  // The same without validation, for inner loops whose s is known to be valid.
  int findSpanUnchecked(double s) const;
  // findSpanUnchecked(s), found without a search when s lies in span `hint` or in the non-empty span
  // after it (parameters asked in order along the curve, or within one known span); any other hint,
  // -1 included, searches. Always the same span as findSpanUnchecked, and unchecked as it is: s must
  // be valid (contains(s)); curvePositionNear is the validated use.
  int findSpanNear(double s, int hint) const;
  // Number of knots exactly equal to s.
  int multiplicity(double s) const;

  // Low-level edits used by knot insertion/removal/splitting, which keep control points in step;
  // prefer insertKnot()/removeKnot() on a curve. They keep the invariants above or throw.
  void insertValue(double s);    // inserts s after the knots equal to it
  void eraseAt(int index);       // removes knots[index]

 private:
  void validate() const;
  int degree_ = 3;
  std::vector<double> knots_;
};

}  // namespace rope
