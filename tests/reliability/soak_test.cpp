// SPDX-License-Identifier: MIT
// Soak runs (label "soak", not in the default run; issue 17): long simulations that must stay healthy.
//   - the knot scene and the pile scene for 10 simulated minutes each;
//   - 100 ropes lying on the ground for 1 simulated minute;
//   - the fuzzers of fuzz_test.cpp twenty times longer, with other seeds.
// Each simulation asserts: resident memory flat after the first simulated minute (growth below
// kMemorySlack), no growth in control points once at rest (the count at the end is no larger than at
// the first minute), and no warning counted by any rope or rope world. Figures are printed.
// About 25 minutes on two cores; run with ctest -L soak.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "demos/scenes/knot_scene.h"
#include "demos/scenes/physics_world.h"
#include "demos/scenes/pile_scene.h"
#include "reliability/fuzz.h"

namespace rope::demos {
namespace {

// Resident memory may move by allocator bookkeeping; a leak of one contact record per substep would
// grow it by megabytes over these runs.
constexpr double kMemorySlack = 1.0 * 1024 * 1024;  // bytes

double residentBytes() {
  std::ifstream statm("/proc/self/statm");
  long size = 0, resident = 0;
  statm >> size >> resident;
  return static_cast<double>(resident) * 4096.0;
}

long warnings(const PhysicsWorld& physics) {
  long total = physics.ropes().warnings().total();
  for (const bullet::RopeObject* rope : physics.ropes().ropes()) total += rope->warnings().total();
  return total;
}

int controlPoints(const PhysicsWorld& physics) {
  int total = 0;
  for (const bullet::RopeObject* rope : physics.ropes().ropes()) total += rope->rod().controlPointCount();
  return total;
}

struct SoakFigures {
  double memoryAtMinute = 0, memoryAtEnd = 0;  // bytes
  int pointsAtMinute = 0, pointsAtEnd = 0, pointsMaxAfterMinute = 0;
  long warnings = 0;
};

// Steps `step` for `seconds` of simulated time at h, sampling the figures at one minute and at the end.
template <class Step>
SoakFigures soak(const char* name, double seconds, double h, Step step, const PhysicsWorld& physics) {
  SoakFigures figures;
  const long steps = std::lround(seconds / h);
  const long minute = std::lround(60.0 / h);
  for (long i = 1; i <= steps; ++i) {
    step();
    if (i == minute) {
      figures.memoryAtMinute = residentBytes();
      figures.pointsAtMinute = controlPoints(physics);
    }
    if (i > minute) figures.pointsMaxAfterMinute = std::max(figures.pointsMaxAfterMinute, controlPoints(physics));
    if (i % minute == 0) {
      std::printf("%s: %ld s, %.1f MiB resident, %d control points, %ld warnings\n", name, std::lround(i * h),
                  residentBytes() / (1024.0 * 1024.0), controlPoints(physics), warnings(physics));
      std::fflush(stdout);
    }
  }
  figures.memoryAtEnd = residentBytes();
  figures.pointsAtEnd = controlPoints(physics);
  figures.warnings = warnings(physics);
  std::printf("%s: memory %.2f MiB at 1 min, %.2f MiB at the end; control points %d at 1 min, %d at the end "
              "(most after 1 min %d); %ld warnings\n",
              name, figures.memoryAtMinute / (1024.0 * 1024.0), figures.memoryAtEnd / (1024.0 * 1024.0),
              figures.pointsAtMinute, figures.pointsAtEnd, figures.pointsMaxAfterMinute, figures.warnings);
  return figures;
}

void expectHealthy(const SoakFigures& figures) {
  EXPECT_LT(figures.memoryAtEnd - figures.memoryAtMinute, kMemorySlack);
  EXPECT_LE(figures.pointsAtEnd, figures.pointsAtMinute);
  EXPECT_EQ(figures.warnings, 0);
}

TEST(Soak, KnotSceneForTenMinutes) {
  KnotScene scene{KnotSceneSettings{}};
  const SoakFigures figures = soak("knot", 600.0, scene.timeStep(), [&] { scene.step(); }, scene.physics());
  expectHealthy(figures);
}

TEST(Soak, PileSceneForTenMinutes) {
  PileScene scene{PileSceneSettings{}};
  const SoakFigures figures = soak("pile", 600.0, scene.timeStep(), [&] { scene.step(); }, scene.physics());
  expectHealthy(figures);
}

TEST(Soak, HundredRopesOnTheGroundForOneMinute) {
  PhysicsWorld physics;
  physics.addGround();
  std::vector<std::unique_ptr<bullet::RopeObject>> ropes;
  RodSettings rod = PileSceneSettings::defaultRod();
  rod.restLength = 0.5;
  for (int i = 0; i < 100; ++i) {
    const double x = 0.6 * (i % 10), z = 0.1 * (i / 10), y = 0.02 + 0.01 * (i % 3);
    ropes.push_back(std::make_unique<bullet::RopeObject>(Rod::fromSegment(rod, Vec3(x, y, z), Vec3(x + 0.5, y, z)),
                                                         PileSceneSettings::defaultBridge()));
    physics.ropes().addRope(*ropes.back());
  }
  const double h = 1.0 / 240.0;
  // The figures at "one minute" are taken at 20 s here (the run is one minute long).
  SoakFigures figures;
  const double memoryAtStart = residentBytes();  // printed: the scene built, nothing stepped
  const long steps = std::lround(60.0 / h), early = std::lround(20.0 / h);
  for (long i = 1; i <= steps; ++i) {
    stepAndCheck(physics, h, "100 ropes");
    if (i == early) {
      figures.memoryAtMinute = residentBytes();
      figures.pointsAtMinute = controlPoints(physics);
    }
  }
  figures.memoryAtEnd = residentBytes();
  figures.pointsAtEnd = controlPoints(physics);
  figures.warnings = warnings(physics);
  double fastest = 0.0;
  for (const auto& rope : ropes) {
    for (const Vec3& v : rope->rod().velocities()) fastest = std::max(fastest, v.norm());
  }
  std::printf("100 ropes: memory %.2f MiB at the start, %.2f MiB at 20 s, %.2f MiB at 60 s; control points %d at 20 s, "
              "%d at 60 s; fastest control point %.2e m/s; %ld warnings\n",
              memoryAtStart / (1024.0 * 1024.0), figures.memoryAtMinute / (1024.0 * 1024.0),
              figures.memoryAtEnd / (1024.0 * 1024.0),
              figures.pointsAtMinute, figures.pointsAtEnd, fastest, figures.warnings);
  expectHealthy(figures);
  EXPECT_LT(fastest, 1e-2);  // at rest on the ground
}

TEST(Soak, FuzzersTwentyTimesLonger) {
  const rope::test::FuzzTotals spline = rope::test::fuzzSplineOperations(0x50a40001, 12000);
  const rope::test::FuzzTotals settings = rope::test::fuzzSettings(0x50a40002, 80000);
  const rope::test::FuzzTotals scene = rope::test::fuzzScene(0x50a40003, 2400, 60);
  std::printf("soak fuzz: %ld spline operations, %ld settings, %ld scene actions (%ld substeps)\n", spline.operations,
              settings.operations, scene.operations, scene.substeps);
}

}  // namespace
}  // namespace rope::demos
