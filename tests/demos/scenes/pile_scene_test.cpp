// SPDX-License-Identifier: MIT
#include "demos/scenes/pile_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "rope/common/error.h"
#include "support/bad_settings.h"

namespace rope::demos {
namespace {

Vec3 centreLineMean(const Rod& rod) {
  constexpr int kSamples = 400;
  Vec3 sum = Vec3::Zero();
  for (int i = 0; i <= kSamples; ++i) {
    sum += rod.position(std::min(rod.endParameter(),
                                 rod.beginParameter() + (rod.endParameter() - rod.beginParameter()) * i / kSamples));
  }
  return sum / (kSamples + 1);
}

TEST(PileScene, DroppedRopePilesUpWithoutPassingThroughItselfAndComesToRest) {
  PileScene scene(PileSceneSettings{});
  const Rod& rod = scene.rope().rod();
  const double diameter = 2.0 * rod.settings().radius;
  double worstOverlap = 0.0, worstPenetration = 0.0;
  int maxSelfContacts = 0;
  Vec3 meanAt5 = Vec3::Zero();
  double heightAt5 = 0.0;
  double speedSum = 0.0;
  int speedSamples = 0;
  const int steps = static_cast<int>(std::lround(5.5 / scene.timeStep()));
  for (int i = 1; i <= steps; ++i) {
    const StepMeasurements m = scene.step();
    worstOverlap = std::max(worstOverlap, m.maxSelfOverlap.value_or(0.0));
    // Measured: at most 0.760 mm (7.6 % of the diameter); bound 1.4 mm.
    ASSERT_LE(m.maxSelfOverlap.value_or(0.0), 0.14 * diameter) << "t = " << scene.time();
    maxSelfContacts = std::max(maxSelfContacts, scene.rope().lastStep().ropeContacts);
    worstPenetration = std::max(worstPenetration, scene.rope().lastStep().maxPenetration);
    if (i == static_cast<int>(std::lround(5.0 / scene.timeStep()))) {
      meanAt5 = centreLineMean(rod);
      heightAt5 = scene.heapHeight();
    }
    if (scene.time() > 5.0) {
      speedSum += std::sqrt(2.0 * rod.kineticEnergy() / rod.mass());
      ++speedSamples;
    }
  }
  const double meanSpeed = speedSum / speedSamples;
  const double drift = (centreLineMean(rod) - meanAt5).norm();
  const double restingPenetration = scene.rope().lastStep().maxPenetration;
  ::testing::Test::RecordProperty("worst_overlap_mm", std::to_string(worstOverlap * 1e3));
  ::testing::Test::RecordProperty("max_self_contacts", std::to_string(maxSelfContacts));
  ::testing::Test::RecordProperty("heap_height_m", std::to_string(scene.heapHeight()));
  ::testing::Test::RecordProperty("rms_speed_after_5s_m_per_s", std::to_string(meanSpeed));
  ::testing::Test::RecordProperty("centre_drift_5_to_5.5s_m", std::to_string(drift));
  ::testing::Test::RecordProperty("worst_ground_penetration_m", std::to_string(worstPenetration));
  std::printf("pile: overlap <= %.3f mm, %d self-contacts at most, heap %.4f m high (%.4f m at 5 s), centre drift "
              "%.3f mm in 0.5 s, rms speed %.2f mm/s, ground penetration %.3f mm at worst, %.3f mm at the end\n",
              worstOverlap * 1e3, maxSelfContacts, scene.heapHeight(), heightAt5, drift * 1e3, meanSpeed * 1e3,
              worstPenetration * 1e3, restingPenetration * 1e3);
  // A heap, not a flat coil: turns rest on turns (the centre line of the top layer at least one
  // diameter above the bottom one) with many self-contacts at once (measured: 2.6 cm high, 33
  // self-contacts at most).
  EXPECT_GT(scene.heapHeight(), rod.settings().radius + diameter);
  EXPECT_LT(scene.heapHeight(), 0.1);
  EXPECT_GE(maxSelfContacts, 25);
  // At rest after 5 s: the heap neither moves nor sinks (measured: centre drift 0.33 mm and height
  // change below 0.05 mm in half a second), and what is left is a jitter (measured rms 7.8 mm/s; it was
  // 4.2 mm/s for the heap the coil made when it also fell under backward Euler: the heap is chaotic in
  // how the coil lands, and the bound 8.5 mm/s stays).
  EXPECT_LT(drift, 5e-4);
  EXPECT_NEAR(scene.heapHeight(), heightAt5, 1e-4);
  EXPECT_LT(meanSpeed, 0.0085);
  // Pushed into the ground by at most 1.6 mm (measured, at impact: the coil lands at 3.1 m/s, 13 mm per
  // step) and 0.18 mm at rest (0.07 mm for the heap of the backward-Euler fall); bounds about 2x.
  EXPECT_LT(worstPenetration, 0.3 * diameter);
  EXPECT_LT(restingPenetration, 3.6e-4);
}

TEST(PileScene, InitialCoilHasItsTurnsApart) {
  const PileSceneSettings settings;
  const PointList points = pileCoilPolyline(settings);
  double length = 0.0;
  for (size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
  EXPECT_NEAR(length, settings.ropeLength, 0.02 * settings.ropeLength);  // chords: a little shorter
  // The rope interpolating the points is unstretched and exactly as long as asked.
  EXPECT_NEAR(PileScene(settings).rope().rod().restLength(), settings.ropeLength, 1e-5 * settings.ropeLength);
  double lowest = std::numeric_limits<double>::infinity();
  for (const Vec3& p : points) lowest = std::min(lowest, p.y());
  EXPECT_NEAR(lowest, settings.dropHeight + settings.rod.radius, 1e-12);
  // Points one turn apart are at least the pitch minus the tilt's shortening apart: > 2 diameters.
  const double turnLength = std::hypot(2.0 * 3.14159265358979323846 * settings.coilRadius, settings.coilPitch);
  double closest = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < points.size(); ++i) {
    for (size_t j = i + 1; j < points.size(); ++j) {
      if (static_cast<double>(j - i) * (length / static_cast<double>(points.size() - 1)) > 0.5 * turnLength) {
        closest = std::min(closest, (points[i] - points[j]).norm());
      }
    }
  }
  EXPECT_GT(closest, 4.0 * settings.rod.radius);
}

TEST(PileScene, RejectsBadSettingsNamingTheField) {
  using S = PileSceneSettings;
  test::expectEachRejected<S>(
      {{"settings.coilPitch", [](S& s) { s.coilPitch = 0.01; }},  // turns would start in contact
       {"settings.tilt", [](S& s) { s.tilt = std::numeric_limits<double>::infinity(); }}},
      [](const S& settings) { PileScene scene(settings); });
}

}  // namespace
}  // namespace rope::demos
