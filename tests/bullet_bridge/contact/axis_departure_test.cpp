// SPDX-License-Identifier: MIT
// The bound of a capsule axis's departure from its curve (bullet_bridge/contact/axis_departure.h): it
// holds at every point of every capsule, is not vacuous (within the worst case 0.385 of the largest
// departure for a cubic piece), and is infinite where no bound is known.
#include "bullet_bridge/contact/axis_departure.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "bullet_bridge/capsule_proxies.h"
#include "bullet_bridge/rope_object.h"

namespace rope::bullet {
namespace {

RodSettings ropeSettings(int degree) {
  RodSettings settings;
  settings.degree = degree;
  settings.restLength = 1.0;
  settings.radius = 0.005;
  settings.initialControlPoints = 12;
  settings.minControlPoints = degree + 1;
  return settings;
}

// A loop and a half of a helix through the polyline interpolation, with knots inserted unevenly, so
// that the spans and their curvature differ.
Rod curvedRod(int degree) {
  PointList points;
  for (int i = 0; i < 12; ++i) {
    const double angle = 0.8 * i;
    points.emplace_back(0.1 * std::cos(angle), 0.1 * std::sin(angle), 0.02 * i + 0.3);
  }
  Rod rod = Rod::fromPolyline(ropeSettings(degree), points);
  const double begin = rod.beginParameter(), end = rod.endParameter();
  for (const double fraction : {0.137, 0.52, 0.53, 0.81}) rod.insertKnot(begin + fraction * (end - begin));
  return rod;
}

double largestDeparture(const CapsuleProxies& proxies, const Rod& rod, int i) {
  const Capsule capsule = proxies.capsule(i);
  const CapsuleProxy& proxy = proxies.proxy(i);
  double largest = 0.0;
  for (int k = 0; k <= 200; ++k) {
    const double t = k / 200.0;
    const btVector3 axis = capsule.a + (capsule.b - capsule.a) * static_cast<btScalar>(t);
    const Vec3 curve = rod.position(proxy.s0 + t * (proxy.s1 - proxy.s0));
    largest = std::max(largest, (Vec3(axis.x(), axis.y(), axis.z()) - curve).norm());
  }
  return largest;
}

TEST(AxisDeparture, BoundsEveryPointOfEveryCapsuleOfACurvedRope) {
  RopeObject owner(Rod::fromSegment(ropeSettings(3), Vec3(0, 0, 0), Vec3(1, 0, 0)));
  const Rod rod = curvedRod(3);
  CapsuleProxies proxies(owner, 4, rod.settings().radius);
  proxies.rebuild(rod);
  std::vector<CurvePoint> scratch;
  std::vector<double> bound;
  double roundoff = -1.0;
  boundAxisDeparture(rod, proxies, scratch, bound, roundoff);
  ASSERT_EQ(static_cast<int>(bound.size()), proxies.size());
  EXPECT_GT(roundoff, 0.0);
  EXPECT_LT(roundoff, 1e-6);
  double worstRatio = 1.0;
  for (int i = 0; i < proxies.size(); ++i) {
    ASSERT_TRUE(std::isfinite(bound[static_cast<size_t>(i)])) << "capsule " << i;
    const double largest = largestDeparture(proxies, rod, i);
    EXPECT_LE(largest, bound[static_cast<size_t>(i)] + roundoff) << "capsule " << i;
    if (bound[static_cast<size_t>(i)] > 1e-9) worstRatio = std::min(worstRatio, largest / bound[static_cast<size_t>(i)]);
  }
  // t (1 - t) |q(t)| reaches at least 0.385 max(|q(0)|, |q(1)|) / 4 (q(1) = -q(0) is the worst case);
  // 201 samples find it to well within 0.35.
  EXPECT_GT(worstRatio, 0.35);
  EXPECT_LE(worstRatio, 1.0 + 1e-9);
}

TEST(AxisDeparture, IsZeroOnAStraightRopeAndInfiniteAboveDegreeThree) {
  RopeObject owner(Rod::fromSegment(ropeSettings(3), Vec3(0, 0, 0), Vec3(1, 0, 0)));
  const Rod straight = Rod::fromSegment(ropeSettings(3), Vec3(0.2, -0.1, 0.3), Vec3(0.9, 0.4, 0.1));
  CapsuleProxies proxies(owner, 4, straight.settings().radius);
  proxies.rebuild(straight);
  std::vector<CurvePoint> scratch;
  std::vector<double> bound;
  double roundoff = 0.0;
  boundAxisDeparture(straight, proxies, scratch, bound, roundoff);
  for (const double b : bound) EXPECT_LT(b, 1e-14);

  const Rod quartic = curvedRod(4);
  CapsuleProxies quarticProxies(owner, 4, quartic.settings().radius);
  quarticProxies.rebuild(quartic);
  boundAxisDeparture(quartic, quarticProxies, scratch, bound, roundoff);
  ASSERT_EQ(static_cast<int>(bound.size()), quarticProxies.size());
  for (const double b : bound) EXPECT_EQ(b, std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace rope::bullet
