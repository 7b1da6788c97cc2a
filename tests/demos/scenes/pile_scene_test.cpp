// SPDX-License-Identifier: MIT
#include "demos/scenes/pile_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

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

// What one drop of the 2 m coil does over 5.5 s (the fall, the impact at about 0.35 s, the heap at rest).
struct PileDrop {
  double worstOverlap = 0.0;      // m, deepest rope-rope overlap at any step
  double worstPenetration = 0.0;  // m, deepest into the ground at any step
  double restingPenetration = 0.0;  // m, at the end
  int maxSelfContacts = 0;
  double height = 0.0;            // m, heap height at the end
  double heightChange = 0.0;      // m, from 5 s to 5.5 s
  double drift = 0.0;             // m, of the centre line's mean from 5 s to 5.5 s
  double meanSpeed = 0.0;         // m/s, rms speed averaged over 5 s .. 5.5 s
};

PileDrop dropPile(double dropHeight) {
  PileSceneSettings settings;
  settings.dropHeight = dropHeight;
  PileScene scene(settings);
  const Rod& rod = scene.rope().rod();
  PileDrop drop;
  Vec3 meanAt5 = Vec3::Zero();
  double heightAt5 = 0.0, speedSum = 0.0;
  int speedSamples = 0;
  const int steps = static_cast<int>(std::lround(5.5 / scene.timeStep()));
  for (int i = 1; i <= steps; ++i) {
    const StepMeasurements m = scene.step();
    drop.worstOverlap = std::max(drop.worstOverlap, m.maxSelfOverlap.value_or(0.0));
    drop.maxSelfContacts = std::max(drop.maxSelfContacts, scene.rope().lastStep().ropeContacts);
    drop.worstPenetration = std::max(drop.worstPenetration, scene.rope().lastStep().maxPenetration);
    if (i == static_cast<int>(std::lround(5.0 / scene.timeStep()))) {
      meanAt5 = centreLineMean(rod);
      heightAt5 = scene.heapHeight();
    }
    if (scene.time() > 5.0) {
      speedSum += std::sqrt(2.0 * rod.kineticEnergy() / rod.mass());
      ++speedSamples;
    }
  }
  drop.restingPenetration = scene.rope().lastStep().maxPenetration;
  drop.height = scene.heapHeight();
  drop.heightChange = std::abs(scene.heapHeight() - heightAt5);
  drop.drift = (centreLineMean(rod) - meanAt5).norm();
  drop.meanSpeed = speedSum / speedSamples;
  return drop;
}

template <typename Field>
std::pair<double, double> medianAndWorst(const std::vector<PileDrop>& drops, Field field) {
  std::vector<double> values;
  for (const PileDrop& drop : drops) values.push_back(static_cast<double>(drop.*field));
  std::sort(values.begin(), values.end());
  return {values[values.size() / 2], values.back()};
}

// The heap is chaotic in how the coil lands: a drop 0.1 mm higher lands differently, so one drop's
// figures are one sample of a spread (measured over eight drops 0.1 mm apart, before and after knot
// insertions gave back the energy they revealed: worst overlap 0.56-3.9 mm, ground penetration
// 1.0-3.3 mm, height change between 5 and 5.5 s 0.02-1.4 mm; the code before: overlap 0.73-9.1 mm,
// penetration 0.72-8.2 mm). So five drops, 0.1 mm apart, are measured: the typical figures are bounded
// through their median, and every drop must stay within the physical limits (no turn passes through
// another, the rope never sinks half a diameter into the ground).
TEST(PileScene, DroppedRopePilesUpWithoutPassingThroughItselfAndComesToRest) {
  const double diameter = 2.0 * PileSceneSettings().rod.radius;
  std::vector<PileDrop> drops;
  for (int k = 0; k < 5; ++k) drops.push_back(dropPile(PileSceneSettings().dropHeight + 1e-4 * k));
  for (const PileDrop& drop : drops) {
    std::printf("pile drop: overlap <= %.3f mm, %d self-contacts at most, heap %.4f m high, ground penetration %.3f "
                "mm at worst, %.3f mm at the end; 5 s to 5.5 s: height change %.3f mm, centre drift %.3f mm, rms "
                "speed %.2f mm/s\n",
                drop.worstOverlap * 1e3, drop.maxSelfContacts, drop.height, drop.worstPenetration * 1e3,
                drop.restingPenetration * 1e3, drop.heightChange * 1e3, drop.drift * 1e3, drop.meanSpeed * 1e3);
    // A heap, not a flat coil: turns rest on turns (the centre line of the top layer at least one
    // diameter above the bottom one) with many self-contacts at once (measured: 2.5-3.5 cm high, 26-46
    // self-contacts at most).
    EXPECT_GT(drop.height, 0.5 * diameter + diameter);
    EXPECT_LT(drop.height, 0.1);
    EXPECT_GE(drop.maxSelfContacts, 25);
    // Physical limits, every drop: no turn passes through another (overlap below half a diameter) or
    // sinks half a diameter into the ground (measured at worst 3.30 mm and 3.33 mm; 3.24 and 3.29 mm
    // without the default material damping, 3.9 and 3.3 mm on earlier code); at rest the ground holds
    // it within 0.36 mm (measured at most 0.10 mm).
    EXPECT_LT(drop.worstOverlap, 0.5 * diameter);
    EXPECT_LT(drop.worstPenetration, 0.5 * diameter);
    EXPECT_LT(drop.restingPenetration, 3.6e-4);
  }
  const auto [overlap, worstOverlap] = medianAndWorst(drops, &PileDrop::worstOverlap);
  const auto [penetration, worstPenetration] = medianAndWorst(drops, &PileDrop::worstPenetration);
  const auto [heightChange, largestHeightChange] = medianAndWorst(drops, &PileDrop::heightChange);
  const auto [drift, largestDrift] = medianAndWorst(drops, &PileDrop::drift);
  const auto [speed, fastest] = medianAndWorst(drops, &PileDrop::meanSpeed);
  std::printf("pile, median (worst) of %zu drops: overlap %.3f (%.3f) mm, ground penetration %.3f (%.3f) mm, height "
              "change %.3f (%.3f) mm, centre drift %.3f (%.3f) mm, rms speed %.2f (%.2f) mm/s\n",
              drops.size(), overlap * 1e3, worstOverlap * 1e3, penetration * 1e3, worstPenetration * 1e3,
              heightChange * 1e3, largestHeightChange * 1e3, drift * 1e3, largestDrift * 1e3, speed * 1e3, fastest * 1e3);
  ::testing::Test::RecordProperty("median_worst_overlap_mm", std::to_string(overlap * 1e3));
  ::testing::Test::RecordProperty("median_worst_ground_penetration_mm", std::to_string(penetration * 1e3));
  ::testing::Test::RecordProperty("median_rms_speed_after_5s_mm_per_s", std::to_string(speed * 1e3));
  // Typical figures through their medians (the README quotes them): overlap 0.68 mm and penetration at
  // impact 2.2 mm (the coil lands at 3.1 m/s, 13 mm per step), within the single drop's old bounds
  // (1.4 and 3 mm; before the banded factor's reciprocal pivots changed the rounding, and so how each
  // coil lands: 1.30 and 1.8 mm; the code before that: medians 1.06 and 2.2 mm over the same five
  // drops); at rest after 5 s a heap that neither moves nor sinks: height change 0.032 mm and centre
  // drift 0.53 mm in half a second (before the reciprocal pivots 0.046 and 0.79 mm; the code before
  // the insertion relaxation: 0.046 and 0.48 mm; the single drop's bounds, 0.1 and 0.5 mm, are at the
  // size of the drop-to-drop spread, 0.01-0.50 mm and 0.27-1.1 mm, so the bounds are 0.36 and 1 mm),
  // and a jitter (rms 4.3 mm/s, 3.5 before the reciprocal pivots, drops 2.0-9.3; bound 8.5 mm/s as
  // before). Measured on the default material damping (1 ms, on top of the scene's own); without it
  // overlap 0.73 mm, impact 2.6 mm, 0.11 mm, 0.58 mm and 3.6 mm/s; before the sliding bounds were
  // solved by GMRES (body_contacts.cpp) 0.88 mm, 0.061 mm, 0.63 mm and 3.7 mm/s, and before removals were capped where friction holds a
  // load (method §10) 0.045 mm, 0.69 mm and 3.6 mm/s.
  EXPECT_LT(overlap, 0.14 * diameter);
  EXPECT_LT(penetration, 0.3 * diameter);
  EXPECT_LT(heightChange, 3.6e-4);
  EXPECT_LT(drift, 1e-3);
  EXPECT_LT(speed, 0.0085);
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
