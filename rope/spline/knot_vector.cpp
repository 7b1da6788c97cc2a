// SPDX-License-Identifier: MIT
#include "rope/spline/knot_vector.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "rope/common/error.h"

namespace rope {
namespace {

std::string knotName(int i) { return "knots[" + std::to_string(i) + "]"; }

void requireDegree(int degree) {
  if (degree < 1 || degree > kMaxDegree) {
    throw InvalidArgument("degree", std::to_string(degree),
                          "must be in 1.." + std::to_string(kMaxDegree));
  }
}

}  // namespace

KnotVector::KnotVector(int degree, std::vector<double> knots) : degree_(degree), knots_(std::move(knots)) {
  validate();
}

void KnotVector::validate() const {
  requireDegree(degree_);
  const int count = size();
  // n >= d+1 control points needs n + d + 1 >= 2d + 2 knots.
  if (count < 2 * degree_ + 2) {
    throw InvalidArgument("knots.size()", std::to_string(count),
                          "degree " + std::to_string(degree_) + " needs at least " +
                              std::to_string(2 * degree_ + 2) + " knots (degree+1 control points)");
  }
  // Finiteness first: an ordered comparison with NaN would raise the "invalid" FP exception.
  for (int i = 0; i < count; ++i) {
    if (!std::isfinite(knots_[static_cast<size_t>(i)])) {
      throw InvalidArgument(knotName(i), formatValue(knots_[static_cast<size_t>(i)]), "must be finite");
    }
  }
  int run = 1;
  for (int i = 1; i < count; ++i) {
    const double previous = knots_[static_cast<size_t>(i - 1)];
    const double current = knots_[static_cast<size_t>(i)];
    if (current < previous) {
      throw InvalidArgument(knotName(i), formatValue(current),
                            "must be >= knots[" + std::to_string(i - 1) + "] = " + formatValue(previous));
    }
    run = current == previous ? run + 1 : 1;
    if (run > degree_ + 1) {
      throw InvalidArgument(knotName(i), formatValue(current),
                            "repeated more than degree+1 = " + std::to_string(degree_ + 1) + " times");
    }
  }
  if (!(validBegin() < validEnd())) {
    throw InvalidArgument(knotName(controlPointCount()), formatValue(validEnd()),
                          "valid range [knots[degree], knots[n]] is empty");
  }
}

KnotVector KnotVector::clampedUniform(int degree, int controlPointCount, double begin, double end) {
  requireDegree(degree);
  if (controlPointCount < degree + 1) {
    throw InvalidArgument("controlPointCount", std::to_string(controlPointCount),
                          "must be >= degree+1 = " + std::to_string(degree + 1));
  }
  requireFinite("begin", begin);
  requireFinite("end", end);
  if (!(begin < end)) throw InvalidArgument("end", formatValue(end), "must be > begin = " + formatValue(begin));
  const int spans = controlPointCount - degree;
  std::vector<double> knots;
  knots.reserve(static_cast<size_t>(controlPointCount + degree + 1));
  for (int i = 0; i <= degree; ++i) knots.push_back(begin);
  for (int j = 1; j < spans; ++j) knots.push_back(begin + (end - begin) * j / spans);
  for (int i = 0; i <= degree; ++i) knots.push_back(end);
  return KnotVector(degree, std::move(knots));
}

KnotVector KnotVector::uniform(int degree, int controlPointCount, double begin, double spacing) {
  requireDegree(degree);
  if (controlPointCount < degree + 1) {
    throw InvalidArgument("controlPointCount", std::to_string(controlPointCount),
                          "must be >= degree+1 = " + std::to_string(degree + 1));
  }
  requireFinite("begin", begin);
  requirePositive("spacing", spacing);
  std::vector<double> knots(static_cast<size_t>(controlPointCount + degree + 1));
  for (size_t i = 0; i < knots.size(); ++i) knots[i] = begin + static_cast<double>(i) * spacing;
  return KnotVector(degree, std::move(knots));
}

bool KnotVector::contains(double s) const {
  return std::isfinite(s) && s >= validBegin() && s <= validEnd();
}

bool KnotVector::isClampedBegin() const { return knots_[0] == knots_[static_cast<size_t>(degree_)]; }

bool KnotVector::isClampedEnd() const {
  return knots_.back() == knots_[knots_.size() - 1 - static_cast<size_t>(degree_)];
}

int KnotVector::findSpan(double s) const {
  if (!contains(s)) {
    throw InvalidArgument("s", formatValue(s),
                          "must lie in the valid range [" + formatValue(validBegin()) + ", " +
                              formatValue(validEnd()) + "]");
  }
  return findSpanUnchecked(s);
}

int KnotVector::findSpanUnchecked(double s) const {
  const int n = controlPointCount();
  const double* begin = knots_.data();
  if (s >= begin[n]) {
    // The right end belongs to the last non-empty span (the end knot may be repeated).
    return static_cast<int>(std::lower_bound(begin + degree_, begin + n, begin[n]) - begin) - 1;
  }
  // First knot among s_{d+1} .. s_{n-1} that is > s; the span starts one before it.
  return static_cast<int>(std::upper_bound(begin + degree_ + 1, begin + n, s) - begin) - 1;
}

int KnotVector::findSpanNear(double s, int hint) const {
  const int last = controlPointCount() - 1;
  if (hint >= degree_ && hint <= last) {
    const double* knots = knots_.data();
    // Span k holds [s_k, s_{k+1}) (the right end of the range is findSpanUnchecked's own case).
    if (s >= knots[hint] && s < knots[hint + 1]) return hint;
    int next = hint + 1;
    while (next < last && knots[next + 1] == knots[next]) ++next;  // skip empty spans
    if (next <= last && s >= knots[next] && s < knots[next + 1]) return next;
  }
  return findSpanUnchecked(s);
}

int KnotVector::multiplicity(double s) const {
  if (!std::isfinite(s)) return 0;
  const auto range = std::equal_range(knots_.begin(), knots_.end(), s);
  return static_cast<int>(range.second - range.first);
}

void KnotVector::insertValue(double s) {
  requireFinite("s", s);
  const auto range = std::equal_range(knots_.begin(), knots_.end(), s);
  if (range.second - range.first >= degree_ + 1) {
    throw InvalidArgument("s", formatValue(s),
                          "already has multiplicity degree+1 = " + std::to_string(degree_ + 1));
  }
  // Inserting keeps the order and adds a control point; the valid range can only grow or stay.
  knots_.insert(range.second, s);
}

void KnotVector::eraseAt(int index) {
  if (index < 0 || index >= size()) {
    throw InvalidArgument("index", std::to_string(index), "must be in 0.." + std::to_string(size() - 1));
  }
  std::vector<double> candidate;
  candidate.reserve(knots_.size() - 1);
  candidate.insert(candidate.end(), knots_.begin(), knots_.begin() + index);
  candidate.insert(candidate.end(), knots_.begin() + index + 1, knots_.end());
  KnotVector checked(degree_, std::move(candidate));  // throws, leaving *this as it was
  knots_ = std::move(checked.knots_);
}

}  // namespace rope
