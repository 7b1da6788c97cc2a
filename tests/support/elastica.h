// SPDX-License-Identifier: MIT
#pragma once
// Test reference: the inextensible elastica of a cantilever clamped horizontally at s = 0 (checked
// against Bisshopp & Drucker, "Large deflection of cantilever beams", Q. Appl. Math. 3 (1945) 272-275,
// in tests/rope/rod/rod_clamp_test.cpp).
// theta(s) is the tangent's angle from the x axis (positive upwards); a downward tip load P and a
// downward weight w per length give the moment balance EI theta' = -P (x_L - x) - int_s^L w (x(t) - x) dt,
// i.e. EI theta'' = (P + w (L - s)) cos theta with theta(0) = 0 (clamp) and theta'(L) = 0 (free
// end). Shooting on theta'(0) with RK4 and bisection.

namespace rope::test {

struct ElasticaTip {
  double x = 0.0;  // m, along the clamp direction
  double y = 0.0;  // m, upwards (negative: deflected down)
};

// Tip of a cantilever of this length (m), bending stiffness EI (N m^2), downward tip load P (N) and
// weight w per metre (N/m).
ElasticaTip elastica(double length, double bendingStiffness, double tipLoad, double weightPerLength);

}  // namespace rope::test
