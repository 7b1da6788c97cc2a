// SPDX-License-Identifier: MIT
// The closed-form tractrix of one segment against the classical tractrix ([B] eq. 1) and a fine
// numerical integration of its ODE (docs/method.md §13), including the degenerate cases.
#include "rope/tractrix/tractrix_segment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rope/common/error.h"

namespace rope {
namespace {

// Classical RK4 on the minimum-displacement ODE: the leading point moves linearly from a to a2 over
// t in [0, 1]; the trailing point moves along the segment, db/dt = (da/dt . t) t, t = (a - b)/|a - b|.
Vec3 integrateTractrixOde(const Vec3& a, const Vec3& b, const Vec3& a2, int steps) {
  const Vec3 velocity = a2 - a;
  auto rate = [&](double time, const Vec3& trailing) -> Vec3 {
    const Vec3 leading = a + time * velocity;
    const Vec3 t = (leading - trailing).normalized();
    return velocity.dot(t) * t;
  };
  Vec3 y = b;
  const double h = 1.0 / steps;
  for (int i = 0; i < steps; ++i) {
    const double time = i * h;
    const Vec3 k1 = rate(time, y);
    const Vec3 k2 = rate(time + 0.5 * h, y + 0.5 * h * k1);
    const Vec3 k3 = rate(time + 0.5 * h, y + 0.5 * h * k2);
    const Vec3 k4 = rate(time + h, y + h * k3);
    y += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return y;
}

TEST(TractrixSegment, ClassicalTractrixMatchesEquationOne) {
  // [B] eq. 1: segment on the Y axis, leading end moved along X: x = q - L tanh(q/L), y = L sech(q/L).
  for (double length : {0.5, 1.0, 3.0}) {
    for (double q : {1e-3, 0.1, 0.5, 1.0, 2.5, 10.0, 40.0}) {
      const Vec3 b2 = tractrixMoveTrailing(Vec3::Zero(), Vec3(0, length, 0), Vec3(q, 0, 0), length);
      EXPECT_NEAR(b2.x(), q - length * std::tanh(q / length), 1e-13 * (1 + q)) << "L=" << length << " q=" << q;
      EXPECT_NEAR(b2.y(), length / std::cosh(q / length), 1e-13 * (1 + q)) << "L=" << length << " q=" << q;
      EXPECT_EQ(b2.z(), 0.0);
    }
  }
}

TEST(TractrixSegment, AgreesWithNumericalOdeIn3D) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0);
  double worst = 0.0;
  for (int trial = 0; trial < 40; ++trial) {
    const Vec3 a(coordinate(rng), coordinate(rng), coordinate(rng));
    const Vec3 b = a + Vec3(coordinate(rng), coordinate(rng), coordinate(rng));
    const Vec3 a2 = a + 2.0 * Vec3(coordinate(rng), coordinate(rng), coordinate(rng));
    const Vec3 closed = tractrixTrailingPoint(a, b, a2);
    const Vec3 numeric = integrateTractrixOde(a, b, a2, 4000);
    worst = std::max(worst, (closed - numeric).norm());
    EXPECT_NEAR((a2 - closed).norm(), (a - b).norm(), 1e-12);
  }
  EXPECT_LT(worst, 1e-6);
  RecordProperty("worst_ode_difference", formatValue(worst));
}

TEST(TractrixSegment, NearlyCollinearCasesAgreeWithOde) {
  // Angles close to 0 and pi, where tan(alpha/2) is 0 or infinite.
  for (double alpha : {1e-6, 1e-3, 0.3, 3.0, 3.14159}) {
    const Vec3 a(0, 0, 0);
    const Vec3 b = -Vec3(std::cos(alpha), std::sin(alpha), 0.0);  // a - b at angle alpha from +x
    const Vec3 a2(1.7, 0, 0);
    const Vec3 closed = tractrixMoveTrailing(a, b, a2, 1.0);
    const Vec3 numeric = integrateTractrixOde(a, b, a2, 20000);
    EXPECT_LT((closed - numeric).norm(), 1e-6) << "alpha=" << alpha;
    EXPECT_NEAR((a2 - closed).norm(), 1.0, 1e-14);
  }
}

TEST(TractrixSegment, DegenerateCasesAreExact) {
  const Vec3 a(1, 2, 3);
  const Vec3 b(1, 2, 1);  // a - b = (0, 0, 2)
  // q = 0: nothing moves, bitwise.
  EXPECT_EQ(tractrixTrailingPoint(a, b, a), b);
  // alpha = 0: moving away along the segment translates it.
  const Vec3 away = tractrixTrailingPoint(a, b, Vec3(1, 2, 4.5));
  EXPECT_NEAR((away - Vec3(1, 2, 2.5)).norm(), 0.0, 1e-15);
  // alpha = pi: moving straight back over the segment (even past the trailing point) translates it.
  const Vec3 back = tractrixTrailingPoint(a, b, Vec3(1, 2, -1));
  EXPECT_NEAR((back - Vec3(1, 2, -3)).norm(), 0.0, 1e-15);
}

TEST(TractrixSegment, LongMovesAlignWithTheDirection) {
  // [B] eq. 2: for q -> infinity the segment aligns with the move, trailing L behind.
  const Vec3 b2 = tractrixMoveTrailing(Vec3::Zero(), Vec3(0, 1, 0), Vec3(1e4, 0, 0), 1.0);
  EXPECT_NEAR(b2.x(), 1e4 - 1.0, 1e-9);
  EXPECT_NEAR(b2.y(), 0.0, 1e-12);
  // Beyond exp underflow (q/L > 745) the limit holds exactly, without FP exceptions.
  const Vec3 far = tractrixMoveTrailing(Vec3::Zero(), Vec3(0, 1, 0), Vec3(1e6, 0, 0), 1.0);
  EXPECT_EQ(far.y(), 0.0);
  EXPECT_NEAR(far.x(), 1e6 - 1.0, 1e-9);
}

TEST(TractrixSegment, TinyMovesStayAccurate) {
  const Vec3 a(0, 0, 0);
  const Vec3 b(-0.6, -0.8, 0);
  for (double q : {1e-9, 1e-150, 1e-300}) {
    const Vec3 b2 = tractrixMoveTrailing(a, b, Vec3(q, 0, 0), 1.0);
    // To first order the trailing point moves by (q u . t) t with t = (0.6, 0.8, 0).
    EXPECT_NEAR((b2 - b).norm(), q * 0.6 + 1e-16, 1e-15) << q;
  }
}

TEST(TractrixSegment, TrailingDisplacementNeverExceedsLeading) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 a(normal(rng), normal(rng), normal(rng));
    const Vec3 b = a + Vec3(normal(rng), normal(rng), normal(rng));
    const Vec3 a2 = a + 3.0 * Vec3(normal(rng), normal(rng), normal(rng));
    const Vec3 b2 = tractrixTrailingPoint(a, b, a2);
    EXPECT_LE((b2 - b).norm(), (a2 - a).norm() * (1 + 1e-14));
  }
}

TEST(TractrixSegment, RejectsBadInput) {
  const double nan = std::nan("");
  const Vec3 a(0, 0, 0);
  const Vec3 b(1, 0, 0);
  EXPECT_THROW(tractrixTrailingPoint(Vec3(nan, 0, 0), b, a), InvalidArgument);
  EXPECT_THROW(tractrixTrailingPoint(a, Vec3(0, HUGE_VAL, 0), a), InvalidArgument);
  EXPECT_THROW(tractrixTrailingPoint(a, b, Vec3(0, 0, nan)), InvalidArgument);
  EXPECT_THROW(tractrixTrailingPoint(a, b, Vec3(0, 0, 1e300)), InvalidArgument);  // would overflow
  EXPECT_THROW(tractrixTrailingPoint(Vec3(-1e200, 0, 0), b, a), InvalidArgument);
  try {
    tractrixTrailingPoint(a, a, b);
    ADD_FAILURE() << "zero-length segment accepted";
  } catch (const InvalidArgument& error) {
    EXPECT_EQ(error.parameter(), "trailing");
  }
}

}  // namespace
}  // namespace rope
