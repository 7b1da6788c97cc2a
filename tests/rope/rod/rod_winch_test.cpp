// SPDX-License-Identifier: MIT
// Paying out and reeling in at an end (Rod::payOut; docs/method.md §16).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "rope/common/error.h"
#include "rope/rod/rod.h"

namespace rope {
namespace {

RodSettings winchSettings() {
  RodSettings settings;
  settings.restLength = 1.0;
  settings.linearDensity = 0.1;
  settings.youngsModulus = 1e7;
  settings.stiffnessDamping = 0.01;
  settings.initialControlPoints = 12;
  return settings;
}

// A bent, moving rope with a curved rest shape: nothing about the operation relies on straightness.
Rod bentRope() {
  PointList points;
  for (int i = 0; i <= 10; ++i) {
    const double u = i / 10.0;
    points.emplace_back(u, 0.2 * std::sin(3.0 * u), 0.1 * u * u);
  }
  Rod rod = Rod::fromPolyline(winchSettings(), points);
  PointList velocities = rod.controlPoints();
  for (Vec3& v : velocities) v = Vec3(v.y(), -v.x(), 0.5 * v.z());
  rod.setVelocities(velocities);
  return rod;
}

TEST(RodWinch, PayingOutKeepsTheRestOfTheRopeAndAddsExactlyItsRestLength) {
  for (Rod::End end : {Rod::End::kBegin, Rod::End::kEnd}) {
    Rod rod = bentRope();
    const Rod before = rod;
    rod.payOut(end, 0.013);
    EXPECT_NEAR(rod.restLength() - before.restLength(), 0.013, 1e-12);
    const double begin = before.beginParameter();
    const double stop = before.endParameter();
    for (int i = 0; i <= 50; ++i) {
      const double s = begin + (stop - begin) * i / 50.0;
      EXPECT_NEAR((rod.position(s) - before.position(s)).norm(), 0.0, 1e-13) << s;
      EXPECT_NEAR((rod.velocity(s) - before.velocity(s)).norm(), 0.0, 1e-13) << s;
      EXPECT_NEAR(rod.restMetric(s), before.restMetric(s), 1e-12) << s;
    }
    // The new piece continues the end polynomial.
    if (end == Rod::End::kBegin) {
      EXPECT_LT(rod.beginParameter(), begin);
      EXPECT_EQ(rod.endParameter(), stop);
    } else {
      EXPECT_GT(rod.endParameter(), stop);
      EXPECT_EQ(rod.beginParameter(), begin);
    }
  }
}

TEST(RodWinch, MassChangesExactlyByLinearDensityTimesLength) {
  for (Rod::End end : {Rod::End::kBegin, Rod::End::kEnd}) {
    Rod rod = Rod::fromSegment(winchSettings(), Vec3(0, 0, 0), Vec3(0, -1, 0));
    const double mass0 = rod.mass();
    double paid = 0.0;
    // 0.5 m out in 1/2400 m steps (0.1 m/s at 240 Hz), then 0.8 m back in.
    for (int i = 0; i < 1200; ++i) {
      rod.payOut(end, 0.1 / 240.0);
      paid += 0.1 / 240.0;
    }
    EXPECT_NEAR(rod.mass() - mass0, 0.1 * paid, 1e-12 * mass0);
    EXPECT_NEAR(rod.restLength(), 1.0 + paid, 1e-12);
    EXPECT_GT(rod.controlPointCount(), 12);  // knots entered at the end
    for (int i = 0; i < 1920; ++i) {
      rod.payOut(end, -0.1 / 240.0);
      paid -= 0.1 / 240.0;
    }
    EXPECT_NEAR(rod.mass() - mass0, 0.1 * paid, 1e-12 * mass0);
    EXPECT_NEAR(rod.restLength(), 1.0 + paid, 1e-12);
    EXPECT_LT(rod.controlPointCount(), 12);  // and left again
    // The rope is still straight along its segment and steps.
    for (int i = 0; i <= 20; ++i) {
      const double s = rod.beginParameter() + (rod.endParameter() - rod.beginParameter()) * i / 20.0;
      EXPECT_NEAR(rod.position(s).x(), 0.0, 1e-12);
      EXPECT_NEAR(rod.position(s).y(), -s, 1e-12);
    }
    EXPECT_TRUE(rod.step(1.0 / 240.0).ok);
  }
}

TEST(RodWinch, APinAtTheEndMovesWithItAndMaterialFlowsAtTheWinchSpeed) {
  // A hanging rope held at its top by a pin at the winch point: paying out 0.1 m/s lowers the
  // material (and the free bottom end) at 0.1 m/s once the motion is steady.
  RodSettings settings = winchSettings();
  settings.massDamping = 0.0;
  Rod rod = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(0, -1, 0));
  const int pin = rod.pin(0.0, Vec3(0, 0, 0));
  for (int i = 0; i < 480; ++i) ASSERT_TRUE(rod.step(1.0 / 240.0).ok);
  const double h = 1.0 / 240.0;
  const double bottom0 = rod.position(rod.endParameter()).y();
  for (int i = 0; i < 240; ++i) {
    rod.payOut(Rod::End::kBegin, 0.1 * h);
    ASSERT_TRUE(rod.step(h).ok);
  }
  ASSERT_EQ(rod.pins().size(), 1u);
  EXPECT_EQ(rod.pins()[0].id, pin);
  EXPECT_EQ(rod.pins()[0].parameter, rod.beginParameter());
  EXPECT_NEAR(rod.beginParameter(), -0.1, 1e-12);
  EXPECT_NEAR(rod.position(rod.beginParameter()).norm(), 0.0, 1e-12);
  const double drop = bottom0 - rod.position(rod.endParameter()).y();
  EXPECT_NEAR(drop, 0.1, 2e-3);  // the rope stretches a little more under its longer weight
}

// Reeling a stiff rope (the crane's: EA = 25 kN) in under a 10 kg load at 0.1 m/s with a knot near the
// winch and a long span after it (a straight rope that adaptivity has coarsened): the knot leaves while
// the end span is still half the nominal spacing, and the material keeps moving at the winch speed.
// Before, it left only when the end span reached minKnotSpacing (5 mm next to about 330 mm), and
// removing it there moved the curve by a strain comparable to the rope's own: undamped, the control
// points were kicked to 88 m/s (knot 30 mm from the end) and 75 m/s (80 mm); in the winch scene with
// stiffnessDamping 10 ms and materialDamping 1 ms the tension rose to 4.4 times the box's weight. Now
// the spread stays at the rope's own axial ringing after the reeling starts, the same with the knot
// anywhere (measured 0.114 m/s undamped, 0.025 m/s damped).
TEST(RodWinch, ReelingInPastAKnotNearTheEndKeepsTheRopeMovingTogether) {
  struct Case {
    double knot;  // m of rest length from the winch end
    double stiffnessDamping, materialDamping;
  };
  for (const Case c : {Case{0.03, 0.0, 0.0}, Case{0.015, 0.01, 1e-3}, Case{0.0091, 0.01, 1e-3}, Case{0.08, 0.0, 0.0}}) {
    RodSettings settings;
    settings.radius = 0.004;
    settings.linearDensity = 0.01;
    settings.youngsModulus = 5.0e8;
    settings.stiffnessDamping = c.stiffnessDamping;
    settings.materialDamping = c.materialDamping;
    settings.adaptive = false;  // the knot stays where it is put
    settings.restLength = 1.3229;
    settings.initialControlPoints = 12;  // the nominal spacing: 0.147 m
    Rod rod = Rod::fromSegment(settings, Vec3(0, 2, 0), Vec3(0, 2 - settings.restLength, 0));
    // Coarsened as adaptivity leaves a straight rope (the winch scene's state when it kicked): one
    // long span of 0.33 m after the knot near the end.
    while (rod.controlPointCount() > rod.degree() + 1) rod.removeKnot(rod.knots()[rod.degree() + 1]);
    rod.insertKnot(rod.beginParameter() + c.knot);
    rod.insertKnot(rod.beginParameter() + 0.3453);
    rod.pin(rod.beginParameter(), Vec3(0, 2, 0));
    rod.addPointMass(rod.endParameter(), 10.0);
    const double h = 1.0 / 240.0;
    for (int i = 0; i < 2400; ++i) ASSERT_TRUE(rod.step(h).ok);
    double spread = 0.0;
    for (int i = 0; i < 300; ++i) {
      rod.payOut(Rod::End::kBegin, -0.1 * h);
      ASSERT_TRUE(rod.step(h).ok) << "knot at " << c.knot << " m, step " << i;
      const PointList& v = rod.velocities();
      if (i < 20) continue;  // the reeling starts from rest: the rope's axial ringing first
      for (const Vec3& u : v) spread = std::max(spread, (u - v.front()).norm());
    }
    std::printf("knot %.4f m from the end: largest velocity spread %.4f m/s, %d control points\n", c.knot, spread,
                rod.controlPointCount());
    EXPECT_LT(spread, 0.15) << "knot at " << c.knot << " m from the end";
  }
}

TEST(RodWinch, BadInputThrowsAndChangesNothing) {
  Rod rod = Rod::fromSegment(winchSettings(), Vec3(0, 0, 0), Vec3(0, -1, 0));
  rod.pin(0.3);
  const Rod before = rod;
  const auto unchanged = [&] {
    EXPECT_EQ(rod.knots().values(), before.knots().values());
    EXPECT_EQ(rod.controlPoints(), before.controlPoints());
    EXPECT_EQ(rod.restControlPoints(), before.restControlPoints());
    EXPECT_EQ(rod.pins()[0].parameter, before.pins()[0].parameter);
  };
  for (double bad : {std::nan(""), double(INFINITY), -double(INFINITY)}) {
    EXPECT_THROW(rod.payOut(Rod::End::kEnd, bad), InvalidArgument);
    unchanged();
  }
  // Reeling past the pin at s = 0.3 from the begin end, or below the minimum length from the other.
  EXPECT_NEAR(rod.reelInLimit(Rod::End::kBegin), 0.3 - rod.settings().minKnotSpacing, 1e-12);
  EXPECT_NEAR(rod.reelInLimit(Rod::End::kEnd), 0.7 - rod.settings().minKnotSpacing, 1e-12);
  try {
    rod.payOut(Rod::End::kBegin, -0.3);
    ADD_FAILURE() << "no throw";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("length"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("-0.29"), std::string::npos) << e.what();
  }
  unchanged();
  EXPECT_THROW(rod.payOut(Rod::End::kEnd, -0.7), InvalidArgument);
  unchanged();
  EXPECT_THROW(rod.payOut(static_cast<Rod::End>(7), 0.1), InvalidArgument);
  unchanged();
  Rod free = Rod::fromSegment(winchSettings(), Vec3(0, 0, 0), Vec3(0, -1, 0));
  EXPECT_THROW(free.payOut(Rod::End::kEnd, -(1.0 - free.minimumRestLength()) - 1e-6), InvalidArgument);
  free.payOut(Rod::End::kEnd, -(1.0 - free.minimumRestLength()));  // down to the minimum works
  EXPECT_NEAR(free.restLength(), free.minimumRestLength(), 1e-12);
  EXPECT_TRUE(free.step(1.0 / 240.0).ok);
}

}  // namespace
}  // namespace rope
