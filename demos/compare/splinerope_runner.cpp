// SPDX-License-Identifier: MIT
// SplineRope side: the demo scenes themselves (crane, drape, thin bar) and, for the catenary and the
// scaling scene, HangScene's rod and pin schedule driven through the public Rod API — HangScene::step()
// also samples the sag at 400 points every step, which would more than double the timed cost of a
// 12-control-point rope; here the sag is sampled only inside the averaging window, outside the timer.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>

#include "demos/compare/runners.h"
#include "demos/compare/scene_specs.h"

namespace rope::compare::splinerope {
namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

double lowestPoint(const Rod& rod, int samples) {
  double lowest = rod.position(rod.beginParameter()).y();
  for (int i = 1; i <= samples; ++i) {
    const double s = rod.beginParameter() + (rod.endParameter() - rod.beginParameter()) * i / samples;
    lowest = std::min(lowest, rod.position(std::min(s, rod.endParameter())).y());
  }
  return lowest;
}

struct PinnedRope {
  Rod rod;
  int left = 0;
  int right = 0;
};

PinnedRope makeCatenary(const CatenarySpec& spec, const Setting& setting, bool adaptive) {
  RodSettings settings = spec.hang.rod;
  settings.restLength = spec.hang.ropeLength;
  settings.initialControlPoints = setting.resolution;
  settings.maxControlPoints = std::max(settings.maxControlPoints, setting.resolution);
  settings.adaptive = adaptive;
  const double half = 0.5 * spec.hang.ropeLength;
  PinnedRope rope{Rod::fromSegment(settings, Vec3(-half, spec.hang.pinHeight, 0), Vec3(half, spec.hang.pinHeight, 0))};
  rope.left = rope.rod.pin(rope.rod.beginParameter());
  rope.right = rope.rod.pin(rope.rod.endParameter());
  return rope;
}

// One HangScene step through the public API; false if the rod refused the step.
bool stepCatenary(const CatenarySpec& spec, PinnedRope& rope, double timeAfterStep, double h) {
  const double half = 0.5 * spec.pinDistance(timeAfterStep);
  rope.rod.setPinTarget(rope.left, Vec3(-half, spec.hang.pinHeight, 0));
  rope.rod.setPinTarget(rope.right, Vec3(half, spec.hang.pinHeight, 0));
  return rope.rod.step(h).ok;
}

Trial catenary(const Setting& setting, const Limits& limits) {
  CatenarySpec spec;
  const double duration = limits.seconds > 0 ? limits.seconds : spec.seconds;
  const double h = spec.hang.timeStep;
  PinnedRope rope = makeCatenary(spec, setting, true);
  Trial trial;
  double sagSum = 0.0;
  int sagSamples = 0;
  const int steps = static_cast<int>(std::lround(duration / h));
  for (int i = 1; i <= steps; ++i) {
    const auto start = Clock::now();
    const bool ok = stepCatenary(spec, rope, i * h, h);
    trial.wallSeconds += seconds(start, Clock::now());
    trial.steps = i;
    trial.simulatedSeconds = i * h;
    if (!ok) {
      trial.status = "step failed";
      break;
    }
    if (trial.wallSeconds > limits.wallBudget) {
      trial.status = "too slow";
      break;
    }
    if (i * h > duration - spec.averagingWindow) {
      sagSum += spec.hang.pinHeight - lowestPoint(rope.rod, 400);
      ++sagSamples;
    }
  }
  trial.dofs = 3 * rope.rod.controlPointCount();
  if (sagSamples > 0) {
    const double sag = sagSum / sagSamples;
    trial.metrics["sag_m"] = sag;
    trial.metrics["sag_error"] = sag / spec.analyticSag() - 1.0;
  }
  trial.metrics["max_strain"] = rope.rod.maxStrain();
  return trial;
}

// Steps a demo scene, timing only step(); `observe` is called after each step outside the timer.
template <class SceneT, class Observe>
void runScene(SceneT& scene, double duration, const Limits& limits, Trial& trial, Observe observe) {
  const double h = scene.timeStep();
  const int steps = static_cast<int>(std::lround(duration / h));
  for (int i = 1; i <= steps; ++i) {
    const auto start = Clock::now();
    try {
      scene.step();
    } catch (const std::exception& error) {
      trial.wallSeconds += seconds(start, Clock::now());
      trial.status = std::string("step failed: ") + error.what();
      return;
    }
    trial.wallSeconds += seconds(start, Clock::now());
    trial.steps = i;
    trial.simulatedSeconds = i * h;
    if (trial.wallSeconds > limits.wallBudget) {
      trial.status = "too slow";
      return;
    }
    observe(i * h);
  }
}

Trial heavyLoad(const Setting& setting, const Limits& limits) {
  HeavyLoadSpec spec;
  if (limits.loadMass > 0) spec.crane.boxMass = limits.loadMass;
  spec.crane.rod.initialControlPoints = setting.resolution;
  spec.crane.rod.maxControlPoints = std::max(spec.crane.rod.maxControlPoints, setting.resolution);
  const double duration = limits.seconds > 0 ? limits.seconds : spec.seconds;
  demos::CraneScene scene(spec.crane);
  Trial trial;
  double strainSum = 0.0;
  int samples = 0;
  runScene(scene, duration, limits, trial, [&](double t) {
    if (t > duration - spec.averagingWindow) {
      strainSum += scene.rope().rod().length() / scene.rope().rod().restLength() - 1.0;
      ++samples;
    }
  });
  trial.dofs = 3 * scene.rope().rod().controlPointCount();
  if (samples > 0) {
    trial.metrics["strain"] = strainSum / samples;
    trial.metrics["strain_error"] = strainSum / samples / spec.expectedStrain() - 1.0;
  }
  return trial;
}

Trial drape(const DrapeSpec& spec, const Setting& setting, const Limits& limits) {
  demos::DrapeSceneSettings settings = spec.drape;
  settings.rod.initialControlPoints = setting.resolution;
  settings.rod.maxControlPoints = std::max(settings.rod.maxControlPoints, setting.resolution);
  const double duration = limits.seconds > 0 ? limits.seconds : spec.seconds;
  demos::DrapeScene scene(settings);
  Trial trial;
  DrapePenetration penetration(spec, duration);
  int maxControlPoints = 0;
  runScene(scene, duration, limits, trial, [&](double t) {
    const Rod& rod = scene.rope().rod();
    maxControlPoints = std::max(maxControlPoints, rod.controlPointCount());
    penetration.sample(t, [&](const auto& visit) {
      constexpr int kSamples = 200;
      for (int i = 0; i <= kSamples; ++i) {
        const double s = rod.beginParameter() + (rod.endParameter() - rod.beginParameter()) * i / kSamples;
        visit(rod.position(std::min(s, rod.endParameter())));
      }
    });
  });
  trial.dofs = 3 * scene.rope().rod().controlPointCount();
  penetration.record(trial.metrics);
  trial.metrics["highest_m"] = scene.highestPoint();
  trial.metrics["max_control_points"] = maxControlPoints;
  return trial;
}

Trial scaling(const Setting& setting, const Limits& limits) {
  ScalingSpec spec;
  const double h = spec.catenary.hang.timeStep;
  PinnedRope rope = makeCatenary(spec.catenary, setting, false);
  Trial trial;
  const double budget = std::min(limits.wallBudget, spec.wallBudget);
  for (int i = 1; i <= spec.warmupSteps + spec.maxSteps; ++i) {
    const auto start = Clock::now();
    const bool ok = stepCatenary(spec.catenary, rope, i * h, h);
    const double wall = seconds(start, Clock::now());
    if (i > spec.warmupSteps) trial.stepSeconds.push_back(wall);
    if (!ok) {
      trial.status = "step failed";
      break;
    }
    if (i <= spec.warmupSteps) continue;
    trial.wallSeconds += wall;
    ++trial.steps;
    trial.simulatedSeconds += h;
    if (trial.wallSeconds > budget && trial.steps >= 2) break;
  }
  trial.dofs = 3 * rope.rod.controlPointCount();
  return trial;
}

}  // namespace

Trial run(Scene scene, const Setting& setting, const Limits& limits) {
  switch (scene) {
    case Scene::kCatenary: return catenary(setting, limits);
    case Scene::kHeavyLoad: return heavyLoad(setting, limits);
    case Scene::kThinBar: return drape(DrapeSpec::thinBar(), setting, limits);
    case Scene::kDrape: return drape(DrapeSpec::box(), setting, limits);
    case Scene::kScaling: return scaling(setting, limits);
  }
  return Trial{};
}

}  // namespace rope::compare::splinerope
