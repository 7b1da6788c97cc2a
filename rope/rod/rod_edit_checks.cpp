// SPDX-License-Identifier: MIT
// Rod: explicit edits the step can live with. A pin the spline has no freedom for, a knot span
// shorter than the rope resolves, or a piece shorter than that, was accepted and then made every
// later step fail (a dependent pin set, a singular step matrix); these refuse them at the call.
#include <algorithm>
#include <string>
#include <vector>

#include "rope/common/error.h"
#include "rope/rod/rod.h"
#include "rope/spline/arc_length.h"

namespace rope {

void Rod::requireIndependentPin(double s) const {
  // Two pins closer than the finest spacing the rope resolves hold the same few control points twice:
  // their constraint rows are nearly equal and every step fails ("pin constraints are dependent"),
  // measured from 1e-7 of a span apart, and from 1e-4 for a stiff rope (E = 1e13 Pa at 1/60 s).
  std::vector<double> parameters{s};
  for (const Pin& other : pins_) {
    const double gap = restDistance(s, other.parameter);
    if (!(gap >= settings_.minKnotSpacing)) {
      throw InvalidArgument("s", formatValue(s),
                            "is " + formatValue(gap) + " m of rest length from the pin at s = " +
                                formatValue(other.parameter) + ", less than settings.minKnotSpacing = " +
                                formatValue(settings_.minKnotSpacing));
    }
    parameters.push_back(other.parameter);
  }
  std::sort(parameters.begin(), parameters.end());
  if (!pinRowsIndependent(knots_, parameters)) {
    throw InvalidArgument("s", formatValue(s),
                          "the spline has no freedom left for another pin here (more pins around s than basis "
                          "functions; insert knots first)");
  }
}

double Rod::restDistance(double a, double b) const {
  return arcLength(knots_, rest_, std::min(a, b), std::max(a, b));
}

void Rod::requireResolvableKnot(double s) const {
  // A new knot value closer to its neighbours than minKnotSpacing makes a span whose own control
  // point has a tiny mass against a huge stretching stiffness: the step matrix then stops being
  // numerically positive definite (measured: a 1e-6 m span on a 1 m nylon rope failed every step at
  // 1/240 s; 1e-4 m did not). Raising the multiplicity of an existing knot adds no span.
  if (knots_.multiplicity(s) > 0) return;
  const int k = knots_.findSpan(s);
  for (const double knot : {knots_[k], knots_[k + 1]}) {
    const double gap = restDistance(s, knot);
    if (!(gap >= settings_.minKnotSpacing)) {
      throw InvalidArgument("s", formatValue(s),
                            "is " + formatValue(gap) + " m of rest length from the knot at " + formatValue(knot) +
                                ", less than settings.minKnotSpacing = " + formatValue(settings_.minKnotSpacing));
    }
  }
}

double Rod::cutPoint(double s) const {
  validateParameter(s);
  const auto requirePieces = [this](double at, double requested) {
    if (!(restDistance(beginParameter(), at) >= settings_.minKnotSpacing) ||
        !(restDistance(at, endParameter()) >= settings_.minKnotSpacing)) {
      throw InvalidArgument("s", formatValue(requested),
                            "would leave a piece shorter than settings.minKnotSpacing = " +
                                formatValue(settings_.minKnotSpacing) + " m of rest length");
    }
  };
  requirePieces(s, s);
  if (knots_.multiplicity(s) > 0) return s;
  // The cut makes s a knot of full multiplicity; a knot closer than minKnotSpacing would leave a
  // span too short to step (as for insertKnot), so the cut moves onto that knot instead.
  const int k = knots_.findSpan(s);
  double at = s;
  double nearest = settings_.minKnotSpacing;
  for (const double knot : {knots_[k], knots_[k + 1]}) {
    if (!(knot > beginParameter() && knot < endParameter())) continue;
    const double gap = restDistance(s, knot);
    if (gap < nearest) {
      nearest = gap;
      at = knot;
    }
  }
  requirePieces(at, s);
  return at;
}

}  // namespace rope
