// Extremes never explode (issue 17): a rope swinging while its knot vector is edited at random, as
// adaptivity and a user's explicit edits might do it at any moment. Asserted: no NaN (traps on), no
// failed step, no point faster than 1.5 times free fall over the rope's length, and, since nothing
// drives the rope (one end pinned, gravity only), the total energy never above its start by more
// than 1 % of m g L (the energy scale of the swing; the total itself depends on the height datum).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "rope/common/error.h"
#include "rope/rod/rod.h"

namespace rope {
namespace {

TEST(Extremes, ThousandRandomKnotInsertionsAndRemovalsDuringASwing) {
  RodSettings settings;
  settings.adaptive = false;  // only the random edits change the knots
  Rod rod = Rod::fromSegment(settings, Vec3(0, 1, 0), Vec3(1, 1, 0));
  rod.pin(0.0);
  const double g = 9.81, length = rod.restLength();
  const double scale = rod.mass() * g * length;
  const double speedBound = 1.5 * std::sqrt(2.0 * g * length);
  const double start = rod.totalEnergy();
  std::mt19937_64 random(17);  // raw outputs only: their sequence is fixed by the standard
  int insertions = 0, removals = 0;
  double highest = start, fastest = 0.0;
  for (int step = 0; step < 2400 && insertions + removals < 2000; ++step) {
    if (random() % 2 == 0) {
      const double s = rod.beginParameter() + (rod.endParameter() - rod.beginParameter()) * ((random() >> 11) * 0x1.0p-53);
      try {
        rod.insertKnot(s);
        ++insertions;
      } catch (const InvalidArgument&) {
        // too close to a knot, or at full multiplicity: refused, nothing changed
      }
    } else {
      const int interior = rod.knots().size() - 2 * (rod.degree() + 1);
      if (interior > 0) {
        rod.removeKnot(rod.knots()[rod.degree() + 1 + static_cast<int>(random() % static_cast<unsigned>(interior))]);
        ++removals;
      }
    }
    const StepReport report = rod.step(1.0 / 240.0);
    ASSERT_TRUE(report.ok) << "step " << step << ": " << report.failure;
    highest = std::max(highest, rod.totalEnergy());
    for (const Vec3& v : rod.velocities()) fastest = std::max(fastest, v.norm());
  }
  std::printf("knot edits during a swing: %d insertions, %d removals, energy growth %.3g of m g L, fastest %.3f m/s "
              "(bound %.3f)\n", insertions, removals, (highest - start) / scale, fastest, speedBound);
  EXPECT_GE(insertions, 500);
  EXPECT_GE(removals, 500);
  EXPECT_LE(highest - start, 0.01 * scale);
  EXPECT_LT(fastest, speedBound);
}

}  // namespace
}  // namespace rope
