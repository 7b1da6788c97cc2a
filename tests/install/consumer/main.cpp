// Builds against the installed headers and library: interpolate a path, insert a knot, check the
// curve did not move.
#include <cmath>
#include <cstdio>

#include "rope/spline/bspline_curve.h"
#include "rope/spline/curve_interpolation.h"

int main() {
  const rope::PointList path = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {2, 1, 1}, {3, 0, 1}};
  rope::BSplineCurve curve = rope::interpolatePolyline(path).curve;
  const double s = 0.37 * curve.endParameter();
  const rope::Vec3 before = curve.position(s);
  curve.insertKnot(0.5 * curve.endParameter());
  const double moved = (curve.position(s) - before).norm();
  std::printf("control points %d, moved %.3g m\n", curve.controlPointCount(), moved);
  return moved < 1e-12 && curve.controlPointCount() == 6 ? 0 : 1;
}
