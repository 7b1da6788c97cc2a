// SPDX-License-Identifier: MIT
#include "reliability/fuzz.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "bullet_bridge/kinematic_rope.h"
#include "bullet_bridge/rope_world.h"
#include "reliability/reliability_support.h"
#include "rope/common/error.h"
#include "rope/rod/rod.h"
#include "rope/tractrix/tractrix_rope.h"
#include "support/fp_exceptions.h"

namespace rope::test {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The fuzzers' choices, from either source (fuzz.h): the helpers below turn raw draws into numbers
// without <random>'s distributions, whose results are implementation-defined.
class Random {
 public:
  virtual ~Random() = default;
  virtual double unit() = 0;      // [0, 1)
  virtual int below(int n) = 0;   // [0, n), n >= 1
  virtual bool exhausted() const { return false; }  // a byte source ran out: end the script
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  bool chance(double p) { return unit() < p; }
  // A value a careless or hostile caller might pass: special values, extremes, or ordinary ones.
  double wild() {
    static const double kPool[] = {kNaN, kInf, -kInf, 0.0, -0.0, -1.0, 1e-300, -1e-300, 1e300, -1e300, 1e-9, 1e9};
    if (chance(0.6)) return kPool[below(static_cast<int>(std::size(kPool)))];
    return (chance(0.5) ? 1.0 : -1.0) * std::pow(10.0, uniform(-6.0, 6.0));
  }
  int wildInt() {
    static const int kPool[] = {0, -1, 1, 2, 3, 64, 65, 1000, 1 << 30, -(1 << 30)};
    return chance(0.7) ? kPool[below(static_cast<int>(std::size(kPool)))] : below(300) - 50;
  }
  Vec3 point(double half) { return Vec3(uniform(-half, half), uniform(-half, half), uniform(-half, half)); }
  btVector3 btPoint(double lo, double hi) {
    return btVector3(btScalar(uniform(lo, hi)), btScalar(uniform(lo, hi)), btScalar(uniform(lo, hi)));
  }
};

// Raw mt19937_64 outputs (their sequence is fixed by the standard): the seeded fuzzers.
class EngineRandom final : public Random {
 public:
  explicit EngineRandom(std::uint64_t seed) : engine_(seed) {}
  double unit() override { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  int below(int n) override { return static_cast<int>(engine_() % static_cast<std::uint64_t>(n)); }

 private:
  std::mt19937_64 engine_;
};

// The bytes of a libFuzzer input or a corpus file, big-endian, as few per draw as the draw needs (one
// byte for a choice among at most 256, four for a number in [0, 1)), so that libFuzzer's byte
// mutations map onto single choices. Past the end every draw is 0.
class ByteRandom final : public Random {
 public:
  ByteRandom(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  double unit() override { return static_cast<double>(take(4)) * 0x1.0p-32; }
  int below(int n) override {
    const int bytes = n <= 0x100 ? 1 : n <= 0x10000 ? 2 : 4;
    return static_cast<int>(take(bytes) % static_cast<std::uint64_t>(n));
  }
  bool exhausted() const override { return position_ >= size_; }

 private:
  std::uint64_t take(int bytes) {
    std::uint64_t value = 0;
    for (int i = 0; i < bytes; ++i) value = (value << 8) | (position_ < size_ ? data_[position_++] : 0u);
    return value;
  }
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t position_ = 0;
};

bool finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

bool finiteState(const Rod& rod) {
  for (const PointList* list : {&rod.controlPoints(), &rod.velocities(), &rod.restControlPoints()})
    for (const Vec3& p : *list)
      if (!finite(p)) return false;
  for (int i = 0; i < rod.knots().size(); ++i)
    if (!std::isfinite(rod.knots()[i])) return false;
  return true;
}

std::vector<Vec3> samples(const Rod& rod, double from, double to, int count = 33) {
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) points.push_back(rod.position(std::min(to, from + (to - from) * i / (count - 1))));
  return points;
}

double largestDistance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
  return worst;
}

double scaleOf(const std::vector<Vec3>& points) {
  double scale = 1.0;
  for (const Vec3& p : points) scale = std::max(scale, p.norm());
  return scale;
}

// A parameter inside [begin, end] or, sometimes, a wild one.
double parameter(Random& random, const Rod& rod, double wildShare = 0.15) {
  if (random.chance(wildShare)) return random.wild();
  return random.uniform(rod.beginParameter(), rod.endParameter());
}

// Runs `call`; a refusal (InvalidArgument, or NumericalFailure where noted by the caller) must leave
// `state()` bit for bit as it was. Returns true if the call was accepted.
template <class Call, class State>
bool refusedLeavesStateAlone(Call call, State state, long& refused, const std::string& what) {
  const std::vector<double> before = state();
  try {
    call();
    return true;
  } catch (const InvalidArgument&) {
    ++refused;
  } catch (const NumericalFailure&) {
    ++refused;
  }
  EXPECT_TRUE(sameBits(state(), before)) << what << ": a refused call changed the state";
  return false;
}

// A rod with a straight rest curve (so mass and momentum are exact polynomial integrals, which
// insertion must keep to round-off), bent and moving at random.
Rod randomRod(Random& random) {
  RodSettings settings;
  settings.degree = 2 + random.below(3);
  settings.minControlPoints = settings.degree + 1;
  settings.initialControlPoints = settings.degree + 1 + random.below(12);
  settings.adaptive = random.chance(0.5);
  settings.youngsModulus = std::pow(10.0, random.uniform(5.0, 10.0));
  Rod rod = Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(1, 0, 0));
  PointList points = rod.controlPoints();
  for (Vec3& p : points) p += random.point(0.2);
  rod.setControlPoints(points);
  PointList velocities(points.size());
  for (Vec3& v : velocities) v = random.point(1.0);
  rod.setVelocities(velocities);
  return rod;
}

// One rod from a random polyline, put through up to maxOperations random operations.
void splineRound(Random& random, int round, int maxOperations, FuzzTotals& totals) {
  Rod rod = randomRod(random);
  bool endRound = false;
  for (int op = 0; op < maxOperations && !endRound && !random.exhausted() && !::testing::Test::HasFailure(); ++op) {
    ++totals.operations;
    const std::string what = "spline round " + std::to_string(round) + " op " + std::to_string(op);
    const auto state = [&rod] { return rodState(rod); };
    const double begin = rod.beginParameter(), end = rod.endParameter();
    switch (random.below(6)) {
      case 0: {  // insertion: the curve, mass and momentum do not move
        const double s = parameter(random, rod);
        const std::vector<Vec3> before = samples(rod, begin, end);
        const double mass = rod.mass();
        const Vec3 momentum = rod.momentum();
        if (!refusedLeavesStateAlone([&] { rod.insertKnot(s); }, state, totals.refused, what)) break;
        ++totals.insertions;
        EXPECT_LE(largestDistance(samples(rod, begin, end), before), 1e-12 * scaleOf(before)) << what;
        EXPECT_LE(std::abs(rod.mass() - mass), 1e-12 * mass) << what;
        EXPECT_LE((rod.momentum() - momentum).norm(), 1e-12 * (momentum.norm() + mass)) << what;
        break;
      }
      case 1: {  // removal: the curve moves by no more than the reported bound
        const int interior = rod.knots().size() - 2 * (rod.degree() + 1);
        const double s = interior > 0 && random.chance(0.85) ? rod.knots()[rod.degree() + 1 + random.below(interior)]
                                                             : parameter(random, rod, 0.5);
        const std::vector<Vec3> before = samples(rod, begin, end);
        RemovalReport report;
        if (!refusedLeavesStateAlone([&] { report = rod.removeKnot(s); }, state, totals.refused, what)) break;
        ++totals.removals;
        EXPECT_LE(largestDistance(samples(rod, begin, end), before), report.positionError + 1e-12 * scaleOf(before))
            << what;
        break;
      }
      case 2: {  // cut: each piece is the curve over its part
        const double s = parameter(random, rod);
        std::optional<std::pair<Rod, Rod>> pieces;
        const auto cut = [&] { pieces.emplace(rod.cut(s)); };
        if (!refusedLeavesStateAlone(cut, state, totals.refused, what)) break;
        ++totals.cuts;
        const double at = rod.cutPoint(s);  // s, or a knot within minKnotSpacing of it
        EXPECT_EQ(pieces->first.endParameter(), at) << what;
        EXPECT_EQ(pieces->second.beginParameter(), at) << what;
        const std::vector<Vec3> left = samples(rod, begin, at), right = samples(rod, at, end);
        EXPECT_LE(largestDistance(samples(pieces->first, begin, at), left), 1e-12 * scaleOf(left)) << what;
        EXPECT_LE(largestDistance(samples(pieces->second, at, end), right), 1e-12 * scaleOf(right)) << what;
        EXPECT_NEAR(pieces->first.mass() + pieces->second.mass(), rod.mass(), 1e-12 * rod.mass()) << what;
        Rod& kept = random.chance(0.5) ? pieces->first : pieces->second;
        if (kept.controlPointCount() >= kept.degree() + 2) rod = std::move(kept);
        break;
      }
      case 3: {  // evaluation
        const double s = parameter(random, rod, 0.3);
        Vec3 p, v, t;
        if (!refusedLeavesStateAlone([&] {
              p = rod.position(s);
              v = rod.velocity(s);
              t = rod.tangent(s);
            }, state, totals.refused, what)) {
          break;
        }
        EXPECT_TRUE(finite(p) && finite(v) && finite(t)) << what;
        break;
      }
      case 4: {  // a step, sometimes with a bad or absurd h
        const double h = random.chance(0.2) ? random.wild() : random.uniform(1e-4, 1.0 / 30.0);
        const std::vector<double> before = state();
        StepReport report;
        // An absurd but valid h (1e300 s, 1e-300 s) overflows inside the step by design; the contract
        // is then a reported failure and an unchanged rod, checked with the traps off.
        const bool absurd = std::isfinite(h) && h > 0.0 && (h < 1e-6 || h > 1.0);
        std::optional<ScopedNoFloatingPointTraps> overflowOnPurpose;
        if (absurd) overflowOnPurpose.emplace();
        if (!refusedLeavesStateAlone([&] { report = rod.step(h); }, state, totals.refused, what)) break;
        if (!report.ok) {
          ++totals.failedSteps;
          EXPECT_TRUE(sameBits(state(), before)) << what << ": a failed step changed the rod";
        }
        EXPECT_TRUE(finiteState(rod)) << what;
        // After a step of 1e9 s the rope may be finite but astronomically large (Rod::step does not
        // judge whether a successful step is plausible): the round ends there.
        if (absurd) endRound = true;
        break;
      }
      default: {  // pins
        if (!rod.pins().empty() && random.chance(0.4)) {
          const int id = random.chance(0.8) ? rod.pins()[static_cast<std::size_t>(random.below(static_cast<int>(rod.pins().size())))].id
                                            : random.wildInt();
          refusedLeavesStateAlone([&] { rod.releasePin(id); }, state, totals.refused, what);
        } else {
          const double s = parameter(random, rod);
          refusedLeavesStateAlone([&] { rod.pin(s); }, state, totals.refused, what);
        }
        break;
      }
    }
    EXPECT_TRUE(finiteState(rod)) << what;
  }
}

}  // namespace

FuzzTotals fuzzSplineOperations(std::uint64_t seed, int rounds) {
  EngineRandom random(seed);
  FuzzTotals totals;
  for (int round = 0; round < rounds && !::testing::Test::HasFailure(); ++round) splineRound(random, round, 60, totals);
  return totals;
}

FuzzTotals fuzzSplineBytes(const std::uint8_t* data, std::size_t size) {
  ByteRandom random(data, size);
  FuzzTotals totals;
  splineRound(random, 0, 64, totals);
  return totals;
}

namespace {

// Sets one numeric field of a settings struct to a wild value.
template <class Settings>
using Mutation = void (*)(Settings&, Random&);

const std::vector<Mutation<RodSettings>>& rodMutations() {
  static const std::vector<Mutation<RodSettings>> m = {
      [](RodSettings& s, Random& r) { s.restLength = r.wild(); },
      [](RodSettings& s, Random& r) { s.radius = r.wild(); },
      [](RodSettings& s, Random& r) { s.linearDensity = r.chance(0.3) ? RodSettings::kDerived : r.wild(); },
      [](RodSettings& s, Random& r) { s.materialDensity = r.wild(); },
      [](RodSettings& s, Random& r) { s.youngsModulus = r.wild(); },
      [](RodSettings& s, Random& r) { s.bendingStiffness = r.chance(0.3) ? RodSettings::kDerived : r.wild(); },
      [](RodSettings& s, Random& r) { s.massDamping = r.wild(); },
      [](RodSettings& s, Random& r) { s.stiffnessDamping = r.wild(); },
      [](RodSettings& s, Random& r) { s.materialDamping = r.wild(); },
      [](RodSettings& s, Random& r) { s.gravity[r.below(3)] = r.wild(); },
      [](RodSettings& s, Random& r) { s.degree = r.wildInt(); },
      [](RodSettings& s, Random& r) { s.initialControlPoints = r.wildInt(); },
      [](RodSettings& s, Random& r) { s.stretchingQuadrature = static_cast<StretchingQuadrature>(r.below(4)); },
      [](RodSettings& s, Random& r) { s.minControlPoints = r.wildInt(); },
      [](RodSettings& s, Random& r) { s.maxControlPoints = r.wildInt(); },
      [](RodSettings& s, Random& r) { s.insertAngle = r.wild(); },
      [](RodSettings& s, Random& r) { s.removeAngle = r.wild(); },
      [](RodSettings& s, Random& r) { s.removalErrorBound = r.wild(); },
      [](RodSettings& s, Random& r) { s.removalVelocityErrorBound = r.wild(); },
      [](RodSettings& s, Random& r) { s.removalCriterion = static_cast<RemovalCriterion>(r.below(4)); },
      [](RodSettings& s, Random& r) { s.removalRelativeError = r.wild(); },
      [](RodSettings& s, Random& r) { s.minKnotSpacing = r.wild(); },
  };
  return m;
}

const std::vector<Mutation<bullet::BulletRopeSettings>>& ropeMutations() {
  using S = bullet::BulletRopeSettings;
  static const std::vector<Mutation<S>> m = {
      [](S& s, Random& r) { s.contactStiffness = r.wild(); },
      [](S& s, Random& r) { s.contactDamping = r.wild(); },
      [](S& s, Random& r) { s.speculativeDamping = r.wild(); },
      [](S& s, Random& r) { s.friction = r.wild(); },
      [](S& s, Random& r) { s.frictionVelocity = r.wild(); },
      [](S& s, Random& r) { s.capsulesPerSpan = r.chance(0.5) ? 1 + r.below(8) : r.wildInt(); },
      [](S& s, Random& r) { s.lineContactStiffness = r.wild(); },
      [](S& s, Random& r) { s.lineContactDamping = r.wild(); },
      [](S& s, Random& r) { s.lineSpeculativeDamping = r.wild(); },
      [](S& s, Random& r) { s.contactQuadraturePoints = r.chance(0.5) ? 1 + r.below(8) : r.wildInt(); },
      [](S& s, Random& r) { s.concentratedContactRatio = r.wild(); },
      [](S& s, Random& r) { s.gravityScale = r.wild(); },
      [](S& s, Random& r) { s.gravitySource = static_cast<S::GravitySource>(r.wildInt()); },
      [](S& s, Random& r) { s.speculativeMargin = r.wild(); },
      [](S& s, Random& r) { s.initialPredictionTime = r.wild(); },
      [](S& s, Random& r) { s.bodyStabilityFactor = r.wild(); },
      [](S& s, Random& r) { s.collisionGroup = r.wildInt(); },
      [](S& s, Random& r) { s.collisionMask = r.wildInt(); },
      [](S& s, Random& r) { s.selfContact = r.chance(0.5); },
      [](S& s, Random& r) { s.selfContactExclusion = r.chance(0.3) ? S::kDerivedExclusion : r.wild(); },
  };
  return m;
}

const std::vector<Mutation<bullet::KinematicRopeSettings>>& hoseMutations() {
  using S = bullet::KinematicRopeSettings;
  static const std::vector<Mutation<S>> m = {
      [](S& s, Random& r) { s.radius = r.wild(); },
      [](S& s, Random& r) { s.capsulesPerSpan = r.chance(0.5) ? 1 + r.below(8) : r.wildInt(); },
      [](S& s, Random& r) { s.speculativeMargin = r.wild(); },
      [](S& s, Random& r) { s.penetrationRecovery = r.wild(); },
      [](S& s, Random& r) { s.friction = r.wild(); },
      [](S& s, Random& r) { s.solverIterations = r.wildInt(); },
      [](S& s, Random& r) { s.collisionGroup = r.wildInt(); },
      [](S& s, Random& r) { s.collisionMask = r.wildInt(); },
  };
  return m;
}

const std::vector<Mutation<TractrixSettings>>& tractrixMutations() {
  using S = TractrixSettings;
  static const std::vector<Mutation<S>> m = {
      [](S& s, Random& r) { s.variant = static_cast<TractrixVariant>(r.below(4)); },
      [](S& s, Random& r) { s.segmentCount = r.chance(0.5) ? 1 + r.below(30) : r.wildInt(); },
      [](S& s, Random& r) { s.degree = r.wildInt(); },
      [](S& s, Random& r) { s.subdivisionAngle = r.chance(0.5) ? r.uniform(0.1, 3.1) : r.wild(); },
      [](S& s, Random& r) { s.mergingAngle = r.chance(0.5) ? r.uniform(0.1, 3.1) : r.wild(); },
      [](S& s, Random& r) { s.minControlPoints = r.wildInt(); },
      [](S& s, Random& r) { s.maxControlPoints = r.wildInt(); },
      [](S& s, Random& r) { s.maxMergeShapeError = r.wild(); },
      [](S& s, Random& r) { s.lengthGaussPoints = r.wildInt(); },
  };
  return m;
}

template <class Settings>
Settings mutated(Random& random, const std::vector<Mutation<Settings>>& mutations) {
  Settings settings;
  const int changes = 1 + random.below(3);
  for (int i = 0; i < changes; ++i) mutations[static_cast<std::size_t>(random.below(static_cast<int>(mutations.size())))](settings, random);
  return settings;
}

void validate(const RodSettings& settings) { settings.validate(); }
void validate(const bullet::BulletRopeSettings& settings) { settings.validate(); }
void validate(const bullet::KinematicRopeSettings& settings) { settings.validate(); }
void validate(const TractrixSettings& settings) { validateTractrixSettings(settings); }

// Validation runs with the traps on (it must never compute with a NaN): true if the settings are
// refused, which must name a "settings." field.
template <class Settings>
bool refused(const Settings& settings, FuzzTotals& totals, const std::string& what) {
  try {
    validate(settings);
    return false;
  } catch (const InvalidArgument& error) {
    ++totals.refused;
    EXPECT_EQ(error.parameter().rfind("settings.", 0), 0u) << what << ": " << error.what();
    return true;
  }
}

// One random settings struct of the given kind (0: RodSettings, 1: BulletRopeSettings, 2:
// KinematicRopeSettings, 3: TractrixSettings): refused naming a field, or simulated for `steps` Bullet
// substeps (half as many rod steps; the tractrix rope is moved ten times).
void settingsRound(Random& random, int round, int kind, int steps, FuzzTotals& totals) {
  const std::string what = "settings round " + std::to_string(round);
  ++totals.operations;
  // Accepted but absurd values (E = 1e300 Pa, a rest length of 1e300 m) overflow inside the rope by
  // design; the contract is then a reported failure and a finite state, checked with the traps off.
  switch (kind) {
    case 0: {
      const RodSettings settings = mutated(random, rodMutations());
      if (refused(settings, totals, what)) break;
      ScopedNoFloatingPointTraps extremeSettingsOverflowOnPurpose;
      std::unique_ptr<Rod> rod;
      EXPECT_NO_THROW(rod = std::make_unique<Rod>(Rod::fromSegment(settings, Vec3(0, 1, 0), Vec3(1, 1, 0)))) << what;
      if (!rod) break;
      EXPECT_TRUE(finiteState(*rod)) << what;
      rod->pin(rod->beginParameter());
      for (int i = 0; i < (steps + 1) / 2; ++i) {
        const std::vector<double> before = rodState(*rod);
        StepReport report;
        EXPECT_NO_THROW(report = rod->step(1.0 / 240.0)) << what;
        if (!report.ok) {
          ++totals.failedSteps;
          EXPECT_TRUE(sameBits(rodState(*rod), before)) << what;
        }
        EXPECT_TRUE(finiteState(*rod)) << what;
      }
      break;
    }
    case 1: {
      const bullet::BulletRopeSettings settings = mutated(random, ropeMutations());
      ActionWorld world;
      world.addBox(btVector3(1, 0.05, 1), 0.0, btVector3(0, 0, 0));
      if (refused(settings, totals, what)) break;
      ScopedNoFloatingPointTraps extremeSettingsOverflowOnPurpose;
      auto rope = std::make_unique<bullet::RopeObject>(
          Rod::fromSegment(RodSettings{}, Vec3(0, 0.1, 0), Vec3(1, 0.1, 0)), settings);
      bullet::RopeWorld ropes(world.world());
      ropes.addRope(*rope);
      EXPECT_NO_THROW(world.step(steps)) << what;
      EXPECT_TRUE(finiteState(rope->rod())) << what;
      totals.failedSteps += rope->warnings().failedSteps;
      break;
    }
    case 2: {
      const bullet::KinematicRopeSettings settings = mutated(random, hoseMutations());
      ActionWorld world;
      world.addBox(btVector3(0.1, 0.1, 0.1), 1.0, btVector3(0.5, 0, 0));
      if (refused(settings, totals, what)) break;
      ScopedNoFloatingPointTraps extremeSettingsOverflowOnPurpose;
      auto hose = std::make_unique<bullet::KinematicRope>(TractrixRope(PointList{Vec3(0, 0, 0), Vec3(1, 0, 0)}), settings);
      hose->addToWorld(world.world());
      hose->followPath([](double t) { return btVector3(btScalar(0.5 * t), 0, btScalar(std::sin(t))); });
      EXPECT_NO_THROW(world.step(steps)) << what;
      for (const Vec3& p : hose->tractrix().controlPoints()) EXPECT_TRUE(finite(p)) << what;
      hose->removeFromWorld();
      break;
    }
    default: {
      const TractrixSettings settings = mutated(random, tractrixMutations());
      if (refused(settings, totals, what)) break;
      ScopedNoFloatingPointTraps extremeSettingsOverflowOnPurpose;
      std::unique_ptr<TractrixRope> rope;
      EXPECT_NO_THROW(rope = std::make_unique<TractrixRope>(PointList{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0)}, settings))
          << what;
      if (!rope) break;
      for (int i = 1; i <= 10; ++i) {
        EXPECT_NO_THROW(rope->moveLeadingEnd(Vec3(-0.1 * i, 0.05 * i, 0))) << what;
        for (const Vec3& p : rope->controlPoints()) EXPECT_TRUE(finite(p)) << what;
      }
      break;
    }
  }
}

}  // namespace

FuzzTotals fuzzSettings(std::uint64_t seed, int rounds) {
  EngineRandom random(seed);
  FuzzTotals totals;
  for (int round = 0; round < rounds && !::testing::Test::HasFailure(); ++round) settingsRound(random, round, round % 4, 10, totals);
  return totals;
}

FuzzTotals fuzzSettingsBytes(const std::uint8_t* data, std::size_t size) {
  ByteRandom random(data, size);
  FuzzTotals totals;
  const int kind = random.below(4);
  settingsRound(random, 0, kind, 2, totals);
  return totals;
}

namespace {

std::vector<double> ropeState(const bullet::RopeObject& rope) {
  std::vector<double> state = rodState(rope.rod());
  for (const bullet::Attachment& a : rope.attachments()) {
    state.insert(state.end(), {static_cast<double>(a.id), a.s, static_cast<double>(a.localPoint.x()),
                               static_cast<double>(a.localPoint.y()), static_cast<double>(a.localPoint.z())});
  }
  state.push_back(rope.world() != nullptr ? 1.0 : 0.0);
  return state;
}

// The objects of one scripted scene.
struct Scene {
  ActionWorld world;
  bullet::RopeWorld ropes{world.world()};
  std::vector<std::unique_ptr<bullet::RopeObject>> ropeObjects;
  std::vector<btRigidBody*> boxes;
  std::unique_ptr<bullet::KinematicRope> hose;

  ~Scene() {
    if (hose) hose->removeFromWorld();
  }
};

btVector3 boundedPoint(Random& random, double lo, double hi) { return random.btPoint(lo, hi); }

// One scene of one or two ropes on a floor (and sometimes a kinematic rope), driven by up to `actions`
// random actions.
void sceneRound(Random& random, int round, int actions, FuzzTotals& totals) {
  Scene scene;
  scene.world.addBox(btVector3(3, 0.1, 3), 0.0, btVector3(0, -0.1, 0));
  const int ropeCount = 1 + random.below(2);
  for (int i = 0; i < ropeCount; ++i) {
    const double y = random.uniform(0.05, 1.0);
    scene.ropeObjects.push_back(std::make_unique<bullet::RopeObject>(
        Rod::fromSegment(RodSettings{}, Vec3(-0.5, y, 0.1 * i), Vec3(0.5, y, 0.1 * i))));
    scene.ropes.addRope(*scene.ropeObjects.back());
  }
  if (random.chance(0.5)) {
    scene.hose = std::make_unique<bullet::KinematicRope>(TractrixRope(PointList{Vec3(0, 0.2, -0.5), Vec3(0, 0.2, 0.5)}));
    scene.hose->addToWorld(scene.world.world());
  }
  for (int action = 0; action < actions && !random.exhausted() && !::testing::Test::HasFailure(); ++action) {
    ++totals.operations;
    const std::string what = "scene round " + std::to_string(round) + " action " + std::to_string(action);
    bullet::RopeObject* rope = scene.ropeObjects.empty()
                                   ? nullptr
                                   : scene.ropeObjects[static_cast<std::size_t>(random.below(static_cast<int>(scene.ropeObjects.size())))].get();
    btRigidBody* box = scene.boxes.empty() ? nullptr
                                            : scene.boxes[static_cast<std::size_t>(random.below(static_cast<int>(scene.boxes.size())))];
    const auto state = [rope] { return rope != nullptr ? ropeState(*rope) : std::vector<double>{}; };
    const int kind = random.below(14);
    switch (kind) {
      case 0:
      case 1: {
        const int substeps = 1 + random.below(4);
        EXPECT_NO_THROW(scene.world.step(substeps)) << what;
        totals.substeps += substeps;
        break;
      }
      case 2: {  // a bad time step reaches the actions (stepSimulation with maxSubSteps = 0)
        static const double kBad[] = {kNaN, -1.0 / 60.0, kInf, 0.0};
        EXPECT_NO_THROW(scene.world.runActions(btScalar(kBad[random.below(4)]))) << what;
        break;
      }
      case 3:
        if (rope == nullptr) break;
        refusedLeavesStateAlone(
            [&] {
              const double s = random.chance(0.8) ? random.uniform(rope->rod().beginParameter(), rope->rod().endParameter())
                                                  : random.wild();
              const btVector3 target = random.chance(0.9) ? boundedPoint(random, -1, 1)
                                                          : btVector3(btScalar(random.chance(0.5) ? kNaN : kInf), 0, 0);
              rope->attachToPoint(s, target);
            },
            state, totals.refused, what);
        break;
      case 4:
        if (rope == nullptr) break;
        refusedLeavesStateAlone(
            [&] {
              const int id = !rope->attachments().empty() && random.chance(0.8)
                                 ? rope->attachments()[static_cast<std::size_t>(random.below(static_cast<int>(rope->attachments().size())))].id
                                 : random.wildInt();
              if (random.chance(0.5)) {
                rope->removeAttachment(id);
              } else {
                rope->setAttachmentTarget(id, boundedPoint(random, -1, 1));
              }
            },
            state, totals.refused, what);
        break;
      case 5:
        if (rope == nullptr || box == nullptr) break;
        refusedLeavesStateAlone(
            [&] {
              const double s = random.chance(0.85) ? random.uniform(rope->rod().beginParameter(), rope->rod().endParameter())
                                                   : random.wild();
              rope->attachToBody(s, *box, boundedPoint(random, -0.05, 0.05));
            },
            state, totals.refused, what);
        break;
      case 6: {
        if (rope == nullptr || scene.ropeObjects.size() >= 6) break;
        std::unique_ptr<bullet::RopeObject> piece;
        refusedLeavesStateAlone(
            [&] {
              const double s = random.chance(0.85) ? random.uniform(rope->rod().beginParameter(), rope->rod().endParameter())
                                                   : random.wild();
              piece = rope->cut(s);
            },
            state, totals.refused, what);
        if (piece) scene.ropeObjects.push_back(std::move(piece));
        break;
      }
      case 7:
        if (scene.boxes.size() < 6) {
          scene.boxes.push_back(scene.world.addBox(btVector3(0.05, 0.05, 0.05), random.uniform(0.01, 10.0),
                                                   boundedPoint(random, 0.1, 1.0)));
        }
        break;
      case 8:  // a body removed and deleted, attached or followed or not
        if (box == nullptr) break;
        scene.world.deleteBody(box);
        scene.boxes.erase(std::find(scene.boxes.begin(), scene.boxes.end(), box));
        break;
      case 9:
        if (box == nullptr) break;
        box->setWorldTransform(btTransform(btQuaternion::getIdentity(), boundedPoint(random, 0.1, 1.0)));
        box->setLinearVelocity(boundedPoint(random, -20, 20));
        box->setAngularVelocity(boundedPoint(random, -20, 20));
        box->activate();
        break;
      case 10:
        if (rope == nullptr) break;
        refusedLeavesStateAlone(
            [&] {
              const double s = random.chance(0.85) ? random.uniform(rope->rod().beginParameter(), rope->rod().endParameter())
                                                   : random.wild();
              // Refused (NaN, inf) or ordinary: an accepted 1e300 N would overflow the next step by design.
              const Vec3 force = random.chance(0.9) ? Vec3(random.point(100.0)) : Vec3(random.chance(0.5) ? kNaN : -kInf, 0, 0);
              rope->rod().addForce(s, force);
            },
            state, totals.refused, what);
        break;
      case 11:
        if (!scene.hose) break;
        switch (random.below(4)) {
          case 0:
            if (box != nullptr) scene.hose->followBodyPoint(box, btVector3(0, 0, 0));
            break;
          case 1:
            scene.hose->setTarget(boundedPoint(random, -1, 1));
            break;
          case 2:
            scene.hose->followPath([](double t) -> btVector3 {
              if (t > 0.05) throw std::runtime_error("scripted path failure");
              return btVector3(0, btScalar(0.2), btScalar(-t));
            });
            break;
          default:
            scene.hose->hold();
        }
        break;
      case 12:  // a rope leaves the world, comes back, or is destroyed
        if (rope == nullptr) break;
        if (random.chance(0.3)) {
          scene.ropeObjects.erase(std::find_if(scene.ropeObjects.begin(), scene.ropeObjects.end(),
                                               [rope](const auto& owned) { return owned.get() == rope; }));
        } else if (rope->world() != nullptr) {
          scene.ropes.removeRope(*rope);
        } else {
          scene.ropes.addRope(*rope);
        }
        break;
      default:  // a rope with a velocity kick, as a user's setVelocities would give it
        if (rope == nullptr) break;
        {
          PointList velocities = rope->rod().velocities();
          for (Vec3& v : velocities) v += random.point(5.0);
          rope->rod().setVelocities(velocities);
        }
        break;
    }
    for (const auto& owned : scene.ropeObjects) EXPECT_TRUE(finiteState(owned->rod())) << what << " (kind " << kind << ")";
  }
  for (const auto& owned : scene.ropeObjects) totals.warnings += owned->warnings().total();
  totals.warnings += scene.ropes.warnings().total();
  if (scene.hose) totals.warnings += scene.hose->warnings().total();
  // Tear down in a random order: ropes before or after the RopeWorld's end of life is checked
  // by the lifetime tests; here the ropes go first, in a shuffled order.
  while (!scene.ropeObjects.empty()) {
    scene.ropeObjects.erase(scene.ropeObjects.begin() + random.below(static_cast<int>(scene.ropeObjects.size())));
  }
}

}  // namespace

FuzzTotals fuzzScene(std::uint64_t seed, int rounds, int actions) {
  EngineRandom random(seed);
  FuzzTotals totals;
  for (int round = 0; round < rounds && !::testing::Test::HasFailure(); ++round) sceneRound(random, round, actions, totals);
  return totals;
}

FuzzTotals fuzzSceneBytes(const std::uint8_t* data, std::size_t size) {
  ByteRandom random(data, size);
  FuzzTotals totals;
  sceneRound(random, 0, 48, totals);
  return totals;
}

}  // namespace rope::test
