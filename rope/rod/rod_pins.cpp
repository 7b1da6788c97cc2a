// Rod: which pins the step can honour ([A] §5.1 pins as constraints; pin_constraints.h).
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
    const double gap = arcLength(knots_, rest_, std::min(s, other.parameter), std::max(s, other.parameter));
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

}  // namespace rope
