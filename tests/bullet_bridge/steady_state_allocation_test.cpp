// SPDX-License-Identifier: MIT
// No heap allocation per step in a steady state (issue 13): once a scene has settled, Bullet's
// stepSimulation with ropes in the world allocates nothing. Every buffer of the rope's step, its
// contacts, adaptivity (removal plans and checks of every candidate knot), the rope-rope coupled
// solve and the report keeps its capacity from one substep to the next.
//
// This program replaces the global operator new (a program of its own for that reason) and counts
// the calls made while only Bullet's step runs (the scenes' own measurements, which build named
// series, are outside the count). Measured before the removal plans worked in place: 200 allocations
// per step in the knot scene and 150 in the capstan scene; a resting rope 2.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <new>

#include "demos/scenes/capstan_scene.h"
#include "demos/scenes/crane_scene.h"
#include "demos/scenes/knot_scene.h"
#include "demos/scenes/resting_rope_scene.h"

namespace {

long gAllocations = 0;  // operator new calls since the program started

void* allocate(std::size_t size) {
  ++gAllocations;
  if (void* p = std::malloc(size > 0 ? size : 1)) return p;
  throw std::bad_alloc();
}

void* allocateAligned(std::size_t size, std::align_val_t alignment) {
  ++gAllocations;
  const std::size_t a = static_cast<std::size_t>(alignment);
  if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a)) return p;
  throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  ++gAllocations;
  return std::malloc(size > 0 ? size : 1);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  ++gAllocations;
  return std::malloc(size > 0 ? size : 1);
}
void* operator new(std::size_t size, std::align_val_t alignment) { return allocateAligned(size, alignment); }
void* operator new[](std::size_t size, std::align_val_t alignment) { return allocateAligned(size, alignment); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace rope::demos {
namespace {

constexpr int kMeasuredSteps = 240;  // one simulated second at 1/240 s

// Settles the scene through its own step() for `settle` s, then counts the allocations of
// kMeasuredSteps steps of Bullet's world alone (the scene's drivers hold still by then).
template <class Scene>
long allocationsPerSecond(Scene& scene, double settle) {
  while (scene.time() < settle - 0.5 * scene.timeStep()) scene.step();
  btDiscreteDynamicsWorld& world = scene.physics().world();
  const btScalar h = static_cast<btScalar>(scene.timeStep());
  const long before = gAllocations;
  for (int i = 0; i < kMeasuredSteps; ++i) world.stepSimulation(h, 1, h);
  const long count = gAllocations - before;
  for (const bullet::RopeStepRecord& rope : scene.physics().ropes().lastReport().ropes) EXPECT_TRUE(rope.ok);
  return count;
}

TEST(SteadyStateAllocation, TenRopesRestingOnABoxAllocateNothing) {
  RestingRopeSceneSettings settings;
  settings.ropeCount = 10;
  RestingRopeScene scene(settings);
  EXPECT_EQ(allocationsPerSecond(scene, 1.0), 0);
}

// Friction holding a load round a drum: removal candidates are planned and checked every step.
TEST(SteadyStateAllocation, RopeHeldByFrictionRoundACylinderAllocatesNothing) {
  CapstanScene scene(CapstanSceneSettings{});
  EXPECT_EQ(allocationsPerSecond(scene, 1.0), 0);
}

// A box hanging on a rope: attachments and their report.
TEST(SteadyStateAllocation, CraneHoldingItsBoxAllocatesNothing) {
  CraneScene scene(CraneSceneSettings{});
  EXPECT_EQ(allocationsPerSecond(scene, 2.0), 0);
}

// The tightened knot held by its grippers (from 3 s; its buffers reach their largest contact set by
// about 5 s): self-contact through the coupled solve every substep.
TEST(SteadyStateAllocation, TightKnotAllocatesNothing) {
  KnotScene scene(KnotSceneSettings{});
  EXPECT_EQ(allocationsPerSecond(scene, 6.0), 0);
}

}  // namespace
}  // namespace rope::demos
