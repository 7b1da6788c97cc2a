// SPDX-License-Identifier: MIT
#include "bullet_bridge/contact/rope_rope_contact.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <tuple>

#include <Eigen/Geometry>

#include "bullet_bridge/contact/axis_departure.h"
#include "bullet_bridge/contact/contact_response.h"
#include "bullet_bridge/detail/radix_sort.h"
#include "bullet_bridge/detail/rest_arc.h"
#include "bullet_bridge/rope_object.h"
#include "bullet_bridge/narrowphase/segment_segment_distance.h"
#include "rope/common/error.h"
#include "rope/spline/gauss_legendre.h"

namespace rope::bullet {

namespace {

constexpr int kMaxSolvePasses = 6;  // small dense solves: contacts switch on and off, friction bounds settle
// With distributed samples: their sliding bounds are re-estimated pass by pass to 1 % (a sample's
// friction is exactly mu times its bound), and round a support each pass carries the bound's error on
// by about mu theta; 6 passes at 5 % left a rope round a taut rope at mu = 1 held at 1.1 exp(mu theta)
// (friction 5-10 % above mu f_n), 12 at 1 % let it slip (measured, capstan scene).
constexpr int kMaxSolvePassesWithSamples = 12;
constexpr double kSampleBoundTolerance = 0.01;
constexpr double kFrictionBoundTolerance = 0.05;
// Relative tolerance on mu f_n before a sticking sample is switched to sliding (round-off of a spring
// exactly at the cone), as for rope-body samples.
constexpr double kConeTolerance = 1e-6;
// Which rope a distributed contact samples (addTouchingStretch): the conditioning of the two
// projections must differ by this much, else the lower (rope, capsule) is sampled.
constexpr double kSampledSideMargin = 0.25;
// The touching stretch of a capsule: within the radii and this share of them of the other axis.
constexpr double kTouchingBand = 0.05;
// A region of touching stretches at least this many contact spacings (r_A + r_B) long is distributed
// (a rope wrapped round or lying along another): it is sampled; shorter ones are crossings, point
// contacts.
constexpr double kDistributedLength = 1.0;
// Length of the chunks of a distributed contact sampled together, in contact spacings (sampleRegion).
constexpr double kChunkLength = 0.5;
// Rest arclength, m, by which the touching stretches of one region may be apart (they share capsule
// ends, where their arclengths are equal up to rounding).
constexpr double kArcJoin = 1e-9;

btVector3 toBullet(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()), static_cast<btScalar>(v.z()));
}

double parameterAt(const CapsuleProxy& proxy, double t) {
  if (t <= 0.0) return proxy.s0;
  if (t >= 1.0) return proxy.s1;  // exactly the neighbour's s0: shared ends give identical contacts
  return std::min(proxy.s1, std::max(proxy.s0, proxy.s0 + t * (proxy.s1 - proxy.s0)));
}

double pointSegmentDistance(const btVector3& p, const btVector3& a, const btVector3& b) {
  const btVector3 axis = b - a;
  const btScalar length2 = axis.length2();
  btScalar t = length2 > 0 ? (p - a).dot(axis) / length2 : btScalar(0);
  t = std::min(btScalar(1), std::max(btScalar(0), t));
  return static_cast<double>((a + axis * t - p).length());
}

// The parameters [lo, hi] of segment p0-p1 within `limit` (m) of segment q0-q1, given the closest
// parameter x (within the limit). The distance to a segment is convex along a segment, so the set is
// one interval; its free ends are bisected to 1/256 of the segment.
void touchingInterval(const btVector3& p0, const btVector3& p1, const btVector3& q0, const btVector3& q1, double x,
                      double limit, double& lo, double& hi) {
  const auto inside = [&](double t) {
    return pointSegmentDistance(p0 + (p1 - p0) * static_cast<btScalar>(t), q0, q1) <= limit;
  };
  const auto bisect = [&](double outside, double in) {
    for (int i = 0; i < 8; ++i) {
      const double middle = 0.5 * (outside + in);
      (inside(middle) ? in : outside) = middle;
    }
    return 0.5 * (outside + in);
  };
  lo = inside(0.0) ? 0.0 : bisect(0.0, x);
  hi = inside(1.0) ? 1.0 : bisect(1.0, x);
}

// The softer of two ropes' laws (each field the smaller value): a stiff rope against a soft one is
// limited by the soft one. Friction is combined as Bullet combines it (friction_combination.h).
ContactLaw pairLaw(const BulletRopeSettings& a, const BulletRopeSettings& b) {
  ContactLaw law;
  law.stiffness = std::min(a.contactStiffness, b.contactStiffness);
  law.damping = std::min(a.contactDamping, b.contactDamping);
  law.speculativeDamping = std::min(a.speculativeDamping, b.speculativeDamping);
  law.friction = combinedFriction(a.friction, b.friction);
  law.frictionVelocity = std::max(a.frictionVelocity, b.frictionVelocity);
  return law;
}

}  // namespace

void RopeRopeContacts::prepare(const std::vector<RopeObject*>& ropes, double h) {
  h_ = h;
  // Per capsule end, once per substep (pairs share capsules many times over): rest arclength and
  // speed; per capsule, its axis's box.
  restArc_.resize(ropes.size());
  ends_.resize(ropes.size());
  boxes_.resize(ropes.size());
  capsuleSpans_.resize(ropes.size());
  bends_.resize(ropes.size());
  facts_.resize(ropes.size());
  deviation_.resize(ropes.size());
  roundoff_.resize(ropes.size());
  for (size_t r = 0; r < ropes.size(); ++r) {
    const Rod& rod = ropes[r]->rod();
    const CapsuleProxies& proxies = ropes[r]->proxies();
    const BulletRopeSettings& settings = ropes[r]->settings();
    facts_[r] = {rod.settings().radius, settings.speculativeMargin,
                 settings.effectiveSelfContactExclusion(rod.settings().radius), settings.selfContact, proxies.size()};
    buildRestArc(rod, restArc_[r]);
    std::vector<CapsuleEnd>& ends = ends_[r];
    std::vector<AxisBox>& boxes = boxes_[r];
    ends.clear();
    boxes.clear();
    deviation_[r].clear();  // made by solve() for the ropes with self-contact hits only
    roundoff_[r] = 0.0;
    if (proxies.size() == 0) continue;  // no pair can name one of its capsules
    ends.resize(static_cast<size_t>(proxies.size()) + 1);
    const std::vector<double>& speeds = proxies.endSpeeds(rod);  // the body contacts' too
    const std::vector<double>& arcs = proxies.endArcs(rod);      // the self-contact walk's too
    for (size_t i = 0; i < ends.size(); ++i) ends[i] = {arcs[i], speeds[i]};
    // Curvature vector of each capsule's stretch of curve (1/m, towards the centre of curvature), from
    // the turn of the chords on either side: what decides which rope a distributed contact samples.
    // Only two different ropes have distributed contacts (a lone rope's knot needs none).
    std::vector<Vec3>& bends = bends_[r];
    bends.assign(static_cast<size_t>(proxies.size()), Vec3::Zero());
    for (int i = 0; ropes.size() > 1 && i < proxies.size(); ++i) {
      const int before = std::max(0, i - 1), after = std::min(proxies.size() - 1, i + 1);
      if (before == after) continue;
      const Capsule c0 = proxies.capsule(before), c1 = proxies.capsule(after);
      const Vec3 d0(c0.b.x() - c0.a.x(), c0.b.y() - c0.a.y(), c0.b.z() - c0.a.z());
      const Vec3 d1(c1.b.x() - c1.a.x(), c1.b.y() - c1.a.y(), c1.b.z() - c1.a.z());
      const double l0 = d0.norm(), l1 = d1.norm();
      if (!(l0 > 0.0 && l1 > 0.0)) continue;
      // The chords' midpoints are (l0 + l1) / 2 apart along the curve, plus the capsule between them.
      double between = 0.5 * (l0 + l1);
      if (after - before == 2) {
        const Capsule c = proxies.capsule(i);
        between += static_cast<double>((c.b - c.a).length());
      }
      bends[static_cast<size_t>(i)] = (d1 / l1 - d0 / l0) / between;
    }
    boxes.resize(static_cast<size_t>(proxies.size()));
    std::vector<int>& spans = capsuleSpans_[r];
    spans.resize(static_cast<size_t>(proxies.size()));
    int span = -1;
    for (int i = 0; i < proxies.size(); ++i) {
      // A capsule lies in one knot span (capsuleEnds): the span search of a parameter on it starts
      // there (it may end in the next one, at the capsule's end).
      span = rod.knots().findSpanNear(proxies.proxy(i).s0, span);
      spans[static_cast<size_t>(i)] = span;
      const Capsule capsule = proxies.capsule(i);
      AxisBox& box = boxes[static_cast<size_t>(i)];
      for (int k = 0; k < 3; ++k) {
        box.low[k] = std::min(capsule.a[k], capsule.b[k]);
        box.high[k] = std::max(capsule.a[k], capsule.b[k]);
      }
      box.speed = std::max(ends[static_cast<size_t>(i)].speed, ends[static_cast<size_t>(i) + 1].speed);
    }
  }
}

bool RopeRopeContacts::mayTouch(const RopeCapsulePair& pair) const {
  const RopeFacts& ropeA = facts_[static_cast<size_t>(pair.ropeA)];
  const RopeFacts& ropeB = facts_[static_cast<size_t>(pair.ropeB)];
  const bool self = pair.ropeA == pair.ropeB;
  if (self && !ropeA.selfContact) return false;
  if (pair.capsuleA >= ropeA.capsules || pair.capsuleB >= ropeB.capsules) return false;
  // Self-pairs whose every point pair is excluded (neighbouring capsules, which always overlap): two
  // thirds of a knot's pairs, in no order a branch predictor could follow, so the tests below are
  // combined without branching (and dropDistantPairs keeps pairs without branching either).
  bool apart = true;
  if (self) {
    const CapsuleEnd* endsA = &ends_[static_cast<size_t>(pair.ropeA)][static_cast<size_t>(pair.capsuleA)];
    const CapsuleEnd* endsB = &ends_[static_cast<size_t>(pair.ropeB)][static_cast<size_t>(pair.capsuleB)];
    apart = !(std::max(std::abs(endsB[1].arc - endsA[0].arc), std::abs(endsA[1].arc - endsB[0].arc)) < ropeA.exclusion);
  }
  // The axes' boxes apart by more than the radii and the reach: the axes are too (most pairs the tree
  // reports in a knot, whose leaves are padded for rope-body contact). A lower bound of the distance,
  // so the exact test in solve decides every pair it lets through, with a relative slack for its
  // rounding.
  const AxisBox& a = boxes_[static_cast<size_t>(pair.ropeA)][static_cast<size_t>(pair.capsuleA)];
  const AxisBox& b = boxes_[static_cast<size_t>(pair.ropeB)][static_cast<size_t>(pair.capsuleB)];
  double gap2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double apart = std::max({0.0, b.low[k] - a.high[k], a.low[k] - b.high[k]});
    gap2 += apart * apart;
  }
  // Compared squared (no square root per pair): the slack covers the rounding either way.
  const double limit = (ropeA.radius + ropeB.radius + reach(pair)) * (1.0 + 1e-9);
  return apart & !(gap2 > limit * limit);
}

void RopeRopeContacts::dropDistantPairs(std::vector<RopeCapsulePair>& pairs) const {
  // In place and in order, as std::remove_if, but each pair is written and the count advanced by the
  // test's outcome rather than branched on.
  size_t kept = 0;
  for (const RopeCapsulePair& pair : pairs) {
    const bool touch = mayTouch(pair);
    pairs[kept] = pair;
    kept += touch ? 1 : 0;
  }
  pairs.resize(kept);
}

RopeRopeContacts::Candidate RopeRopeContacts::contactBetween(int ropeA, double sA, double arcA, int ropeB, double sB,
                                                             double arcB, double radii, double centres,
                                                             const Vec3& normal) {
  Candidate candidate;
  candidate.record = -1;
  candidate.ropeA = ropeA;
  candidate.ropeB = ropeB;
  candidate.sA = sA;
  candidate.sB = sB;
  candidate.arcA = arcA;
  candidate.arcB = arcB;
  candidate.spacing = radii;
  candidate.distance = centres - radii;
  candidate.normal = normal;
  candidate.frictionNormalForce = -1.0;
  candidate.active = false;
  candidate.relativeVelocity = Vec3::Zero();
  candidate.coupled = false;
  return candidate;
}

void RopeRopeContacts::addTouchingStretch(const std::vector<RopeObject*>& ropes, const RopeCapsulePair& pair,
                                          double closestS, double closestT, double closestDistance, const Vec3& normal,
                                          double centres, int candidate) {
  const Capsule capsuleA = ropes[static_cast<size_t>(pair.ropeA)]->proxies().capsule(pair.capsuleA);
  const Capsule capsuleB = ropes[static_cast<size_t>(pair.ropeB)]->proxies().capsule(pair.capsuleB);
  const RopeFacts& a = facts_[static_cast<size_t>(pair.ropeA)];
  const RopeFacts& b = facts_[static_cast<size_t>(pair.ropeB)];
  const double radii = a.radius + b.radius;
  // Which rope is sampled: a point of one rope has a well-defined closest point on the other unless
  // the other curves round it (a rope wrapped round a taut one: every point of the wrap is equally
  // near the taut rope's axis point). With D the distance of the axes and kappa the curvature towards
  // the other rope, projecting onto rope X is conditioned by c_X = 1 - D kappa_X (1: straight, 0: X
  // curves round the point at exactly D). The sampled rope is the one that curves round the other;
  // within kSampledSideMargin of each other (two straight ropes) the lower (rope, capsule).
  const Vec3& bendA = bends_[static_cast<size_t>(pair.ropeA)][static_cast<size_t>(pair.capsuleA)];
  const Vec3& bendB = bends_[static_cast<size_t>(pair.ropeB)][static_cast<size_t>(pair.capsuleB)];
  const double conditionA = 1.0 + centres * bendA.dot(normal);  // A curves towards B: bendA along -normal
  const double conditionB = 1.0 - centres * bendB.dot(normal);
  const bool sampleB = conditionA > conditionB + kSampledSideMargin;
  // The touching stretch of the sampled capsule's axis: within the radii (plus a sliver of them) of
  // the other axis. Not the gap the step can close: ropes that are still approaching meet as point
  // contacts (a fast rope crossing another would otherwise be "distributed" over a stretch as long as
  // its step, and could pass between samples spread along it).
  const double limit = radii * (1.0 + kTouchingBand);
  if (!(closestDistance <= limit)) return;
  Stretch stretch;
  stretch.candidate = candidate;
  stretch.reach = reach(pair);
  if (sampleB) {
    stretch.sampledRope = pair.ropeB;
    stretch.sampledCapsule = pair.capsuleB;
    stretch.otherRope = pair.ropeA;
    stretch.otherCapsule = pair.capsuleA;
    touchingInterval(capsuleB.a, capsuleB.b, capsuleA.a, capsuleA.b, closestT, limit, stretch.lo, stretch.hi);
  } else {
    stretch.sampledRope = pair.ropeA;
    stretch.sampledCapsule = pair.capsuleA;
    stretch.otherRope = pair.ropeB;
    stretch.otherCapsule = pair.capsuleB;
    touchingInterval(capsuleA.a, capsuleA.b, capsuleB.a, capsuleB.b, closestS, limit, stretch.lo, stretch.hi);
  }
  const CapsuleEnd* ends = &ends_[static_cast<size_t>(stretch.sampledRope)][static_cast<size_t>(stretch.sampledCapsule)];
  stretch.arcLo = ends[0].arc + stretch.lo * (ends[1].arc - ends[0].arc);
  stretch.arcHi = ends[0].arc + stretch.hi * (ends[1].arc - ends[0].arc);
  stretches_.push_back(stretch);
}

void RopeRopeContacts::sampleDistributedContacts(const std::vector<RopeObject*>& ropes) {
  samples_.clear();
  if (stretches_.empty()) return;
  // Regions: touching stretches of one sampled rope against one other rope that meet along the sampled
  // rope's rest curve.
  std::sort(stretches_.begin(), stretches_.end(), [](const Stretch& x, const Stretch& y) {
    return std::tie(x.sampledRope, x.otherRope, x.arcLo, x.sampledCapsule, x.otherCapsule) <
           std::tie(y.sampledRope, y.otherRope, y.arcLo, y.sampledCapsule, y.otherCapsule);
  });
  size_t first = 0;
  while (first < stretches_.size()) {
    size_t last = first + 1;
    double arcHi = stretches_[first].arcHi;
    while (last < stretches_.size() && stretches_[last].sampledRope == stretches_[first].sampledRope &&
           stretches_[last].otherRope == stretches_[first].otherRope && stretches_[last].arcLo <= arcHi + kArcJoin) {
      arcHi = std::max(arcHi, stretches_[last].arcHi);
      ++last;
    }
    const double radii = facts_[static_cast<size_t>(stretches_[first].sampledRope)].radius +
                         facts_[static_cast<size_t>(stretches_[first].otherRope)].radius;
    // Shorter than the contact spacing: a crossing, concentrated at one point (the point contacts).
    if (arcHi - stretches_[first].arcLo >= kDistributedLength * radii) {
      for (size_t k = first; k < last; ++k) candidates_[static_cast<size_t>(stretches_[k].candidate)].suppressed = true;
      sampleRegion(ropes, first, last);
    }
    first = last;
  }
}

void RopeRopeContacts::sampleRegion(const std::vector<RopeObject*>& ropes, size_t first, size_t last) {
  // Gauss-Legendre nodes on chunks of the sampled rope, bins of kChunkLength contact spacings of its
  // rest arclength: consecutive sampled capsules in one bin whose touching stretches continue one
  // another along one strand of the other rope are sampled together, so that the number of samples
  // follows the length in contact, not the resolution (a rope refined round a wrap has capsules of
  // about a millimetre; every sample is a coupling of the dense contact solve, cubic in their
  // number). A capsule touching two strands of the other rope is sampled once per strand.
  std::sort(stretches_.begin() + static_cast<std::ptrdiff_t>(first), stretches_.begin() + static_cast<std::ptrdiff_t>(last),
            [](const Stretch& x, const Stretch& y) {
              return std::tie(x.sampledCapsule, x.otherCapsule) < std::tie(y.sampledCapsule, y.otherCapsule);
            });
  const RopeObject& sampled = *ropes[static_cast<size_t>(stretches_[first].sampledRope)];
  const double spacing = facts_[static_cast<size_t>(stretches_[first].sampledRope)].radius +
                         facts_[static_cast<size_t>(stretches_[first].otherRope)].radius;
  const auto parameter = [&](const Stretch& stretch, double t) {
    return parameterAt(sampled.proxies().proxy(stretch.sampledCapsule), t);
  };
  // The open chunk: stretches [chunkFirst, chunkEnd), parameters [chunkS0, chunkS1].
  size_t chunkFirst = first, chunkEnd = first;
  double chunkS0 = 0.0, chunkS1 = 0.0, chunkHi = 0.0, chunkBin = 0.0;
  int chunkCapsule = -1, chunkOtherHigh = -1;
  const auto flush = [&] {
    if (chunkEnd > chunkFirst) sampleRun(ropes, chunkFirst, chunkEnd, chunkS0, chunkS1);
    chunkFirst = chunkEnd;
  };
  size_t block = first;
  while (block < last) {
    size_t blockEnd = block + 1;
    bool oneStrand = true;
    while (blockEnd < last && stretches_[blockEnd].sampledCapsule == stretches_[block].sampledCapsule) {
      oneStrand = oneStrand && stretches_[blockEnd].otherCapsule <= stretches_[blockEnd - 1].otherCapsule + 1;
      ++blockEnd;
    }
    double lo = stretches_[block].lo, hi = stretches_[block].hi;
    for (size_t k = block + 1; k < blockEnd; ++k) {
      lo = std::min(lo, stretches_[k].lo);
      hi = std::max(hi, stretches_[k].hi);
    }
    const int capsule = stretches_[block].sampledCapsule;
    const int otherLow = stretches_[block].otherCapsule, otherHigh = stretches_[blockEnd - 1].otherCapsule;
    // Chunks are bins of the rest arclength, which is material: their nodes stay where they are while
    // the rope holds still (sticking springs are carried per parameter, rope_stick_memory.h).
    const double bin = std::floor(ends_[static_cast<size_t>(stretches_[block].sampledRope)][static_cast<size_t>(capsule)].arc /
                                  (kChunkLength * spacing));
    const bool continues = chunkEnd > chunkFirst && capsule == chunkCapsule + 1 && chunkHi >= 1.0 && lo <= 0.0 &&
                           otherLow <= chunkOtherHigh + 1 && otherHigh + 1 >= chunkOtherHigh && bin == chunkBin;
    if (!continues) flush();
    if (!oneStrand) {
      // Per run of consecutive capsules of the other rope, this capsule alone.
      size_t run = block;
      while (run < blockEnd) {
        size_t runEnd = run + 1;
        double runLo = stretches_[run].lo, runHi = stretches_[run].hi;
        while (runEnd < blockEnd && stretches_[runEnd].otherCapsule <= stretches_[runEnd - 1].otherCapsule + 1) {
          runLo = std::min(runLo, stretches_[runEnd].lo);
          runHi = std::max(runHi, stretches_[runEnd].hi);
          ++runEnd;
        }
        sampleRun(ropes, run, runEnd, parameter(stretches_[run], runLo), parameter(stretches_[run], runHi));
        run = runEnd;
      }
      chunkFirst = chunkEnd = blockEnd;
      chunkCapsule = -1;
      block = blockEnd;
      continue;
    }
    if (chunkEnd == chunkFirst) chunkS0 = parameter(stretches_[block], lo);
    chunkEnd = blockEnd;
    chunkS1 = parameter(stretches_[block], hi);
    chunkHi = hi;
    chunkCapsule = capsule;
    chunkOtherHigh = otherHigh;
    chunkBin = bin;
    block = blockEnd;
  }
  flush();
}

void RopeRopeContacts::sampleRun(const std::vector<RopeObject*>& ropes, size_t first, size_t last, double s0,
                                 double s1) {
  const Stretch& head = stretches_[first];
  const RopeObject& sampled = *ropes[static_cast<size_t>(head.sampledRope)];
  const RopeObject& other = *ropes[static_cast<size_t>(head.otherRope)];
  const Rod& rodS = sampled.rod();
  const Rod& rodO = other.rod();
  const RopeFacts& factsS = facts_[static_cast<size_t>(head.sampledRope)];
  const RopeFacts& factsO = facts_[static_cast<size_t>(head.otherRope)];
  const double radii = factsS.radius + factsO.radius;
  double reach = head.reach;
  for (size_t k = first + 1; k < last; ++k) reach = std::max(reach, stretches_[k].reach);
  if (!(s1 > s0)) return;
  // Two ropes only (self-contact stays point contacts); two pieces cut from one rope are one rope
  // near their cut.
  const RopeObject::CutPartner* cut = nullptr;
  for (const RopeObject::CutPartner& partner : sampled.cutPartners()) {
    if (partner.rope == &other) cut = &partner;
  }
  const GaussRule rule = gaussLegendre(sampled.settings().contactQuadraturePoints);
  for (int q = 0; q < rule.count; ++q) {
    const double s = 0.5 * (s0 + s1) + 0.5 * (s1 - s0) * rule.nodes[q];
    const Vec3 point = rodS.position(s);
    const btVector3 p = toBullet(point);
    // The nearest axis point of the run's capsules, then one Newton step on the other curve.
    int nearest = head.otherCapsule;
    double nearestT = 0.0, nearestDistance = 1e300;
    for (size_t k = first; k < last; ++k) {
      const Capsule c = other.proxies().capsule(stretches_[k].otherCapsule);
      const btVector3 axis = c.b - c.a;
      const btScalar length2 = axis.length2();
      btScalar t = length2 > 0 ? (p - c.a).dot(axis) / length2 : btScalar(0);
      t = std::min(btScalar(1), std::max(btScalar(0), t));
      const double distance = static_cast<double>((c.a + axis * t - p).length());
      if (distance < nearestDistance) {
        nearestDistance = distance;
        nearest = stretches_[k].otherCapsule;
        nearestT = static_cast<double>(t);
      }
    }
    const CapsuleProxy& otherProxy = other.proxies().proxy(nearest);
    double sO = parameterAt(otherProxy, nearestT);
    {
      const Capsule c = other.proxies().capsule(nearest);
      const double width = otherProxy.s1 - otherProxy.s0;
      const double speed = width > 0.0 ? static_cast<double>((c.b - c.a).length()) / width : 0.0;
      if (speed > 0.0) {
        const Vec3 q0 = rodO.position(sO);
        const double step = rodO.tangent(sO).dot(point - q0) / speed;
        sO = std::clamp(sO + std::clamp(step, -width, width), rodO.beginParameter(), rodO.endParameter());
      }
    }
    const double arcS = restArcAt(rodS, restArc_[static_cast<size_t>(head.sampledRope)], s);
    const double arcO = restArcAt(rodO, restArc_[static_cast<size_t>(head.otherRope)], sO);
    if (cut != nullptr) {
      const double cutS = restArcAt(rodS, restArc_[static_cast<size_t>(head.sampledRope)], cut->ownEnd);
      const double cutO = restArcAt(rodO, restArc_[static_cast<size_t>(head.otherRope)], cut->partnerEnd);
      if (std::abs(arcS - cutS) + std::abs(arcO - cutO) < sampled.settings().effectiveSelfContactExclusion(rodS.settings().radius))
        continue;
    }
    Vec3 normal = point - rodO.position(sO);
    double centres = normal.norm();
    if (!(centres > 1e-12 * radii)) continue;  // centre lines meet: the point contacts decide
    normal /= centres;
    if (!(centres - radii < reach)) continue;
    Candidate candidate = contactBetween(head.sampledRope, s, arcS, head.otherRope, sO, arcO, radii, centres, normal);
    candidate.sample = true;
    candidate.weight = 0.5 * (s1 - s0) * rule.weights[q] * rodS.restMetric(s);
    samples_.push_back(candidate);
  }
}

void RopeRopeContacts::startSample(const RopeObject& sampled, const RopeObject& other, Candidate& candidate) const {
  // The sample's share of the line law: the point law's stiffness, damping and speculative damping
  // per contact spacing (r_A + r_B) of rope, times the rest length the sample stands for.
  const double share = candidate.weight / candidate.spacing;
  candidate.law.stiffness *= share;
  candidate.law.damping *= share;
  candidate.law.speculativeDamping *= share;
  SampleFriction& friction = candidate.friction;
  friction = SampleFriction{};
  const Vec3& n = candidate.normal;
  const Vec3 slip = candidate.relativeVelocity - n * n.dot(candidate.relativeVelocity);
  const double speed = slip.norm();
  const double v = candidate.law.frictionVelocity;
  Vec3 stretch = Vec3::Zero();
  bool wasSliding = false;
  const double reach = candidate.spacing / std::max(sampled.rod().restMetric(candidate.sA), 1e-12);  // parameter units
  const bool remembered = memory_.find(sampled, other, candidate.sA, reach, stretch, wasSliding);
  if (speed >= v && (!remembered || wasSliding)) {
    friction.sliding = true;
    friction.direction = slip / speed;
    friction.speed = speed;
    friction.normalForce = std::max(0.0, -candidate.law.stiffness * candidate.distance);
  } else {
    friction.displacement = stretch - n * n.dot(stretch);  // in today's tangent plane
  }
}

CouplingLaw RopeRopeContacts::lawOf(const Candidate& candidate, double h) const {
  CouplingLaw law;
  if (!candidate.active) return law;
  // The contact law in the relative velocity (the "body" at rest in B's frame): f0, K, D. Samples
  // carry rope-body samples' law (sticking spring, exact sliding force), point contacts the
  // regularised one.
  const ContactSpring spring =
      candidate.sample
          ? sampleSpring(candidate.law, candidate.distance, candidate.normal, candidate.relativeVelocity, Vec3::Zero(), h,
                         candidate.friction)
          : contactSpring(candidate.law, candidate.distance, candidate.normal, candidate.relativeVelocity, Vec3::Zero(),
                          h, candidate.frictionNormalForce);
  law.impulse = h * (spring.force - h * (spring.stiffness * candidate.relativeVelocity));
  law.admittance = h * h * spring.stiffness + h * spring.damping;
  return law;
}

bool RopeRopeContacts::updateSampleFriction(Candidate& candidate, int k, double normalForce, double h) {
  if (!(candidate.law.friction > 0.0)) return false;
  SampleFriction& friction = candidate.friction;
  const Vec3 force = impulses_[static_cast<size_t>(k)] / h;
  const Vec3& n = candidate.normal;
  if (!friction.sliding) {
    const Vec3 tangentForce = force - n * n.dot(force);
    const double magnitude = tangentForce.norm();
    if (magnitude <= candidate.law.friction * normalForce * (1.0 + kConeTolerance)) return false;
    // The spring would need more than mu f_n: the sample slides, along the way the force pushes it.
    const Vec3 w = candidate.relativeVelocity + solver_.solvedRelativeChange(k);
    friction.sliding = true;
    friction.direction = -tangentForce / magnitude;
    friction.speed = std::max((w - n * n.dot(w)).norm(), candidate.law.frictionVelocity);
    friction.normalForce = normalForce;
    return true;
  }
  if (std::abs(normalForce - friction.normalForce) <= kSampleBoundTolerance * std::max(normalForce, friction.normalForce))
    return false;
  friction.normalForce = normalForce;
  return true;
}

void RopeRopeContacts::rememberSampleFriction(const std::vector<RopeObject*>& ropes, double h) {
  for (size_t k = 0; k < couplings_.size(); ++k) {
    const Candidate& candidate = candidates_[static_cast<size_t>(coupled_[k])];
    if (!candidate.sample || !candidate.active || !(candidate.law.friction > 0.0) || !(candidate.law.stiffness > 0.0))
      continue;
    const Vec3 force = impulses_[k] / h;
    const Vec3& n = candidate.normal;
    const double normalForce = std::max(0.0, n.dot(force));
    const double limit = candidate.law.friction * normalForce;
    const Vec3 w = candidate.relativeVelocity + solver_.solvedRelativeChange(static_cast<int>(k));
    const Vec3 slip = w - n * n.dot(w);
    Vec3 stretch;
    bool sliding = false;
    if (!candidate.friction.sliding) {
      // The spring's stretch at the end of the step, kept within the friction cone.
      stretch = candidate.friction.displacement + h * slip;
    } else {
      // One that puts the spring at the friction force the sample ends the step with, so that it
      // keeps carrying its load if it sticks again.
      const Vec3 tangentForce = force - n * n.dot(force);
      stretch = -tangentForce / candidate.law.stiffness;
      sliding = slip.norm() >= candidate.law.frictionVelocity && slip.dot(candidate.friction.direction) > 0.0;
    }
    const double springForce = candidate.law.stiffness * stretch.norm();
    if (springForce > limit && springForce > 0.0) stretch *= limit / springForce;
    memory_.add(*ropes[static_cast<size_t>(candidate.ropeA)], *ropes[static_cast<size_t>(candidate.ropeB)], candidate.sA,
                stretch, sliding);
  }
  memory_.commit();
}

RopeRopeContacts::Candidate RopeRopeContacts::pointContact(const Rod& rodA, const Rod& rodB, const Hit& hit,
                                                            double spacing, double* centresOut) {
  // The spans found here are kept as hints for the candidate's later evaluations (velocities, record).
  int spanA = hit.spanA, spanB = hit.spanB;
  const Vec3 pointA = curvePositionNear(rodA.knots(), rodA.controlPoints(), hit.sA, spanA);
  const Vec3 pointB = curvePositionNear(rodB.knots(), rodB.controlPoints(), hit.sB, spanB);
  Vec3 normal = pointA - pointB;
  double centres = normal.norm();
  if (centres > 1e-12 * spacing) {
    normal /= centres;
  } else {
    // Centre lines meet: separate across both tangents (or any direction normal to A's).
    normal = rodA.tangent(hit.sA).cross(rodB.tangent(hit.sB));
    if (!(normal.norm() > 1e-9)) normal = rodA.tangent(hit.sA).unitOrthogonal();
    normal.normalize();
    centres = 0.0;
  }
  if (centresOut != nullptr) *centresOut = centres;
  // law, relativeVelocity and coupled: for the kept candidates only, after the thinning.
  Candidate candidate = contactBetween(hit.ropeA, hit.sA, hit.arcA, hit.ropeB, hit.sB, hit.arcB, spacing, centres, normal);
  candidate.spanA = spanA;
  candidate.spanB = spanB;
  return candidate;
}

int RopeRopeContacts::solve(const std::vector<RopeObject*>& ropes, const std::vector<RopeCapsulePair>& pairs,
                            double h, std::vector<RopePairContactRecord>& records) {
  detect(ropes, pairs);
  return respond(ropes, h, records);
}

void RopeRopeContacts::detect(const std::vector<RopeObject*>& ropes, const std::vector<RopeCapsulePair>& pairs) {
  candidates_.clear();
  stretches_.clear();
  hits_.clear();

  // ---- narrowphase, at the ropes' state before the step ----
  for (const RopeCapsulePair& pair : pairs) {
    const RopeObject& ropeA = *ropes[static_cast<size_t>(pair.ropeA)];
    const RopeObject& ropeB = *ropes[static_cast<size_t>(pair.ropeB)];
    const Rod& rodA = ropeA.rod();
    const Rod& rodB = ropeB.rod();
    const bool self = pair.ropeA == pair.ropeB;
    const CapsuleProxy& proxyA = ropeA.proxies().proxy(pair.capsuleA);
    const CapsuleProxy& proxyB = ropeB.proxies().proxy(pair.capsuleB);
    const double exclusion = ropeA.settings().effectiveSelfContactExclusion(rodA.settings().radius);
    const std::vector<double>& arcA = restArc_[static_cast<size_t>(pair.ropeA)];
    const CapsuleEnd* endsA = &ends_[static_cast<size_t>(pair.ropeA)][static_cast<size_t>(pair.capsuleA)];
    const CapsuleEnd* endsB = &ends_[static_cast<size_t>(pair.ropeB)][static_cast<size_t>(pair.capsuleB)];
    // mayTouch (dropDistantPairs) has kept only pairs with both capsules present, a self-pair with
    // some point pair outside the exclusion, and axes' boxes within reach.
    // Two pieces cut from one rope count as one rope near their cut (their ends start overlapping).
    const RopeObject::CutPartner* cut = nullptr;
    if (!self) {
      for (const RopeObject::CutPartner& partner : ropeA.cutPartners()) {
        if (partner.rope == &ropeB) cut = &partner;
      }
    }
    double cutArcA = 0.0, cutArcB = 0.0;
    if (cut != nullptr) {
      cutArcA = restArcAt(rodA, arcA, cut->ownEnd);
      cutArcB = restArcAt(rodB, restArc_[static_cast<size_t>(pair.ropeB)], cut->partnerEnd);
    }
    if (cut != nullptr) {
      const double farthest = std::max(std::abs(endsA[0].arc - cutArcA), std::abs(endsA[1].arc - cutArcA)) +
                              std::max(std::abs(endsB[0].arc - cutArcB), std::abs(endsB[1].arc - cutArcB));
      if (farthest < exclusion) continue;
    }
    const Capsule capsuleA = ropeA.proxies().capsule(pair.capsuleA);
    const Capsule capsuleB = ropeB.proxies().capsule(pair.capsuleB);
    const double radii = rodA.settings().radius + rodB.settings().radius;
    const double reach = this->reach(pair);
    const SegmentPairClosest closest = segmentSegmentClosest(capsuleA.a, capsuleA.b, capsuleB.a, capsuleB.b);
    if (!(closest.distance - radii < reach)) continue;

    const double sA = parameterAt(proxyA, closest.s);
    const double sB = parameterAt(proxyB, closest.t);
    // A capsule lies inside one knot span, where the rest arclength is linear in s (restArcAt), and s
    // is linear along the capsule: interpolate between its ends' arclengths (no span search).
    const double arcSA = endsA[0].arc + std::clamp(static_cast<double>(closest.s), 0.0, 1.0) * (endsA[1].arc - endsA[0].arc);
    const double arcSB = endsB[0].arc + std::clamp(static_cast<double>(closest.t), 0.0, 1.0) * (endsB[1].arc - endsB[0].arc);
    if (self && std::abs(arcSA - arcSB) < exclusion) continue;
    if (cut != nullptr && std::abs(arcSA - cutArcA) + std::abs(arcSB - cutArcB) < exclusion) continue;

    // Written in place, member by member: a Hit assembled on the stack and copied in stalled on the
    // copy's wide loads of the narrow stores just made (store forwarding; 1 % of the knot's step).
    Hit& hit = hits_.emplace_back();
    hit.gap = closest.distance - radii;
    hit.sA = sA;
    hit.sB = sB;
    hit.arcA = arcSA;
    hit.arcB = arcSB;
    hit.ropeA = pair.ropeA;
    hit.ropeB = pair.ropeB;
    hit.candidate = -1;
    hit.spanA = capsuleSpans_[static_cast<size_t>(pair.ropeA)][static_cast<size_t>(pair.capsuleA)];
    hit.spanB = capsuleSpans_[static_cast<size_t>(pair.ropeB)][static_cast<size_t>(pair.capsuleB)];
    if (self) {
      // Until evaluated on the curve, the gap's lower bound: the axes' gap less both axes' departure
      // from the curve (axis_departure.h; once per substep for a rope with self-contact hits).
      std::vector<double>& deviation = deviation_[static_cast<size_t>(pair.ropeA)];
      double& roundoff = roundoff_[static_cast<size_t>(pair.ropeA)];
      if (deviation.empty()) boundAxisDeparture(rodA, ropeA.proxies(), endCurve_, deviation, roundoff);
      hit.gap -= deviation[static_cast<size_t>(pair.capsuleA)] + deviation[static_cast<size_t>(pair.capsuleB)] + 2.0 * roundoff;
    } else {
      // Two ropes: the curve now, for the touching stretch (which rope curves round the other).
      double centres = 0.0;
      candidates_.push_back(pointContact(rodA, rodB, hit, radii, &centres));
      hit.candidate = static_cast<int>(candidates_.size()) - 1;
      hit.gap = candidates_.back().distance;
      addTouchingStretch(ropes, pair, closest.s, closest.t, closest.distance, candidates_.back().normal, centres,
                         hit.candidate);
    }
  }
  sampleDistributedContacts(ropes);

  // One contact per place: neighbouring capsule pairs find the same crossing (or the same stretch of a
  // side-by-side contact) several times. Deepest first on the curve, by (gap, ropeA, sA, ropeB, sB); a
  // hit within one contact spacing (the sum of the radii, along both rest curves) of an accepted one is
  // dropped, so a line contact is sampled about once per diameter. Hits with equal keys are the same
  // contact found twice (one point, the same everything), so their order does not matter.
  // Lazily, with the same result: a tight knot has some 900 hits for 25 contacts, and most are dropped
  // before their curve points are needed. The hits are taken in the order of a lower bound of their gap
  // (the axes'); one near an accepted hit is dropped at once (the accepted one is deeper than even the
  // bound); one that is not is evaluated on the curve and waits, by its exact gap, until no bound below
  // it remains.
  const auto before = [](const Hit& a, const Hit& b) {
    return std::tie(a.gap, a.ropeA, a.sA, a.ropeB, a.sB) < std::tie(b.gap, b.ropeA, b.sA, b.ropeB, b.sB);
  };
  // Sorted through small keys (a hit is 64 bytes), by the gap's leading 4 bytes in linear time (sign,
  // exponent and 20 bits of mantissa: gaps within a millionth of each other share one, and half the
  // passes of a sort by the whole gap); each run of equal leading keys is then ordered by the whole
  // key, stably: the order is the whole key's either way.
  constexpr int kGapKeyBytes = 4;
  order_.clear();
  for (size_t c = 0; c < hits_.size(); ++c) {
    const Hit& hit = hits_[c];
    // Inside a distributed contact, which its samples carry.
    if (hit.candidate >= 0 && candidates_[static_cast<size_t>(hit.candidate)].suppressed) continue;
    KeyedIndex& keyed = order_.emplace_back();  // in place, as the hits above
    keyed.key = hit.gap;
    keyed.index = static_cast<int>(c);
  }
  radixSortByKey(order_, orderScratch_, kGapKeyBytes);
  for (size_t first = 0; first < order_.size();) {
    const std::uint64_t run = leadingKey(order_[first].key, kGapKeyBytes);
    size_t last = first + 1;
    while (last < order_.size() && leadingKey(order_[last].key, kGapKeyBytes) == run) ++last;
    // Stably: a run comes out of the radix sort by increasing index, which breaks the whole key's ties
    // (std::sort then, not stable_sort, which may allocate; O(k log k) also for long runs, such as
    // straight ropes side by side whose hits share one gap).
    if (last - first > 1) {
      std::sort(order_.begin() + static_cast<std::ptrdiff_t>(first), order_.begin() + static_cast<std::ptrdiff_t>(last),
                [&](const KeyedIndex& a, const KeyedIndex& b) {
                  const Hit& x = hits_[static_cast<size_t>(a.index)];
                  const Hit& y = hits_[static_cast<size_t>(b.index)];
                  if (before(x, y)) return true;
                  return !before(y, x) && a.index < b.index;
                });
    }
    first = last;
  }
  // The accepted ones are also kept ordered by (ropeA, ropeB, arcA), so each test looks only at those
  // within one spacing along A: O(c log c) instead of comparing every hit with every accepted one.
  // (Spelled out: std::tie compares each member twice, and this runs some 5 times per hit.)
  const auto byArc = [](const Accepted& x, const Accepted& y) {
    if (x.ropeA != y.ropeA) return x.ropeA < y.ropeA;
    if (x.ropeB != y.ropeB) return x.ropeB < y.ropeB;
    return x.arcA < y.arcA;
  };
  const auto nearAccepted = [&](const Hit& hit) {
    const double spacing = this->spacing(hit.ropeA, hit.ropeB);
    const Accepted from{hit.ropeA, hit.ropeB, hit.arcA - spacing, hit.arcB};
    // std::lower_bound(keptByArc_, from, byArc), each halving chosen by a select instead of a branch:
    // every hit asks, and the mispredicted branches of std::lower_bound were about 4 % of the 2 m
    // pile's step (perf: 2,700 hits per substep). [first, first + length] holds the answer throughout.
    const Accepted* first = keptByArc_.data();
    const Accepted* const end = first + keptByArc_.size();
    for (std::ptrdiff_t length = end - first; length > 1;) {
      const std::ptrdiff_t half = length / 2;
      first = byArc(first[half - 1], from) ? first + half : first;
      length -= half;
    }
    if (first != end && byArc(*first, from)) ++first;
    for (const Accepted* it = first; it != end; ++it) {
      const Accepted& other = *it;
      if (other.ropeA != hit.ropeA || other.ropeB != hit.ropeB || !(other.arcA < hit.arcA + spacing)) break;
      if (std::abs(other.arcA - hit.arcA) < spacing && std::abs(other.arcB - hit.arcB) < spacing) return true;
    }
    return false;
  };
  // Evaluated hits waiting, smallest key on top.
  const auto after = [&](int x, int y) { return before(hits_[static_cast<size_t>(y)], hits_[static_cast<size_t>(x)]); };
  waiting_.clear();
  keptByArc_.clear();
  kept_.clear();
  size_t next = 0;
  while (next < order_.size() || !waiting_.empty()) {
    int index;
    if (!waiting_.empty() &&
        (next == order_.size() ||
         !before(hits_[static_cast<size_t>(order_[next].index)], hits_[static_cast<size_t>(waiting_.front())]))) {
      std::pop_heap(waiting_.begin(), waiting_.end(), after);
      index = waiting_.back();
      waiting_.pop_back();
    } else {
      index = order_[next++].index;
    }
    Hit& hit = hits_[static_cast<size_t>(index)];
    if (nearAccepted(hit)) continue;
    if (hit.candidate < 0) {
      candidates_.push_back(pointContact(ropes[static_cast<size_t>(hit.ropeA)]->rod(),
                                         ropes[static_cast<size_t>(hit.ropeB)]->rod(), hit, spacing(hit.ropeA, hit.ropeB)));
      hit.candidate = static_cast<int>(candidates_.size()) - 1;
      hit.gap = candidates_.back().distance;
      waiting_.push_back(index);
      std::push_heap(waiting_.begin(), waiting_.end(), after);
      continue;
    }
    kept_.push_back(candidates_[static_cast<size_t>(hit.candidate)]);
    const Accepted accepted{hit.ropeA, hit.ropeB, hit.arcA, hit.arcB};
    keptByArc_.insert(std::upper_bound(keptByArc_.begin(), keptByArc_.end(), accepted, byArc), accepted);
  }
  candidates_.swap(kept_);
  candidates_.insert(candidates_.end(), samples_.begin(), samples_.end());
}

int RopeRopeContacts::respond(const std::vector<RopeObject*>& ropes, double h,
                              std::vector<RopePairContactRecord>& records) {
  for (Candidate& candidate : candidates_) {
    const RopeObject& ropeA = *ropes[static_cast<size_t>(candidate.ropeA)];
    const RopeObject& ropeB = *ropes[static_cast<size_t>(candidate.ropeB)];
    candidate.law = pairLaw(ropeA.settings(), ropeB.settings());
    if (combiner_) {
      candidate.law.friction = combiner_(ropeA, ropeB);
      if (!(std::isfinite(candidate.law.friction) && candidate.law.friction >= 0.0)) {
        throw InvalidArgument("rope friction combiner", formatValue(candidate.law.friction),
                              "must return a finite value >= 0");
      }
    }
    // Rod::velocity and Rod::position, bitwise, from the spans pointContact found (a sample's: searched).
    const Rod& rodA = ropeA.rod();
    const Rod& rodB = ropeB.rod();
    candidate.relativeVelocity = curvePositionNear(rodA.knots(), rodA.velocities(), candidate.sA, candidate.spanA) -
                                 curvePositionNear(rodB.knots(), rodB.velocities(), candidate.sB, candidate.spanB);
    candidate.coupled = ropeA.rod().hasTrial() && ropeB.rod().hasTrial();
    if (candidate.sample) startSample(ropeA, ropeB, candidate);
  }
  for (Candidate& candidate : candidates_) {
    const RopeObject& ropeA = *ropes[static_cast<size_t>(candidate.ropeA)];
    const RopeObject& ropeB = *ropes[static_cast<size_t>(candidate.ropeB)];
    RopePairContactRecord record;
    record.ropeA = &ropeA;
    record.ropeB = &ropeB;
    record.sA = candidate.sA;
    record.sB = candidate.sB;
    record.pointA = toBullet(curvePositionNear(ropeA.rod().knots(), ropeA.rod().controlPoints(), candidate.sA, candidate.spanA));
    record.pointB = toBullet(curvePositionNear(ropeB.rod().knots(), ropeB.rod().controlPoints(), candidate.sB, candidate.spanB));
    record.normal = toBullet(candidate.normal);
    record.depth = -candidate.distance;
    record.weight = candidate.sample ? candidate.weight : 0.0;
    candidate.record = static_cast<int>(records.size());
    records.push_back(record);
  }

  // ---- implicit coupled response ----
  // Rods with a trial, and their index in the coupled solve (-1: the rope's step failed).
  rodIndex_.assign(ropes.size(), -1);
  std::vector<int>& rodIndex = rodIndex_;
  rods_.clear();
  for (size_t r = 0; r < ropes.size(); ++r) {
    if (!ropes[r]->rod().hasTrial()) continue;
    rodIndex[r] = static_cast<int>(rods_.size());
    rods_.push_back(&ropes[r]->rod());
  }
  // Every candidate whose gap the step can close enters the coupled system, acting or not, so that the
  // active set below can switch it on when the solve predicts the tubes would overlap at the end of
  // the step (gravity and the rope's own forces close gaps the start-of-step velocity does not).
  couplings_.clear();
  coupled_.clear();
  for (size_t c = 0; c < candidates_.size(); ++c) {
    Candidate& candidate = candidates_[c];
    if (!candidate.coupled) continue;
    candidate.active = contactActive(candidate.distance, candidate.normal, candidate.relativeVelocity, Vec3::Zero(), h);
    couplings_.push_back({rodIndex[static_cast<size_t>(candidate.ropeA)], candidate.sA,
                          rodIndex[static_cast<size_t>(candidate.ropeB)], candidate.sB, !candidate.sample});
    coupled_.push_back(static_cast<int>(c));
  }
  if (couplings_.empty()) {
    memory_.commit();  // nothing acts: no sample carries a stick state into the next substep
    return 0;
  }

  solver_.prepare(rods_, couplings_);
  laws_.resize(couplings_.size());
  for (size_t k = 0; k < couplings_.size(); ++k) laws_[k] = lawOf(candidates_[static_cast<size_t>(coupled_[k])], h);

  bool solved = false;
  const int maxPasses = samples_.empty() ? kMaxSolvePasses : kMaxSolvePassesWithSamples;
  for (int pass = 1; pass <= maxPasses; ++pass) {
    solved = solver_.solveImpulses(laws_, impulses_);
    if (!solved || pass == maxPasses) break;
    bool changed = false;
    for (size_t k = 0; k < couplings_.size(); ++k) {
      Candidate& candidate = candidates_[static_cast<size_t>(coupled_[k])];
      if (!candidate.active) {
        // Switched on when the tubes would end the step overlapping.
        const Vec3 w = candidate.relativeVelocity + solver_.solvedRelativeChange(static_cast<int>(k));
        if (!(candidate.distance + h * candidate.normal.dot(w) < 0.0)) continue;
        candidate.active = true;
      } else {
        const double normalForce = candidate.normal.dot(impulses_[k]) / h;
        if (normalForce < 0.0) {
          candidate.active = false;  // pulling: the tubes separate during the step
        } else if (candidate.sample) {
          if (!updateSampleFriction(candidate, static_cast<int>(k), normalForce, h)) continue;
        } else if (candidate.law.friction > 0.0) {
          const double estimate = candidate.frictionNormalForce >= 0.0
                                      ? candidate.frictionNormalForce
                                      : std::max(0.0, -candidate.law.stiffness * candidate.distance);
          if (std::abs(normalForce - estimate) <= kFrictionBoundTolerance * std::max(normalForce, estimate)) continue;
          candidate.frictionNormalForce = normalForce;
        } else {
          continue;
        }
      }
      laws_[k] = lawOf(candidate, h);
      changed = true;
    }
    if (!changed) break;
  }
  if (!solved) {
    // The ropes keep their uncoupled trials; the contacts are reported as not acting.
    for (const int c : coupled_) candidates_[static_cast<size_t>(c)].active = false;
    return -1;
  }
  solver_.apply(impulses_);
  rememberSampleFriction(ropes, h);

  int active = 0;
  for (size_t k = 0; k < couplings_.size(); ++k) {
    const Candidate& candidate = candidates_[static_cast<size_t>(coupled_[k])];
    if (!candidate.active) continue;
    RopePairContactRecord& record = records[static_cast<size_t>(candidate.record)];
    record.active = true;
    record.force = toBullet(impulses_[k] / h);
    if (candidate.sample) {
      record.sticking = candidate.law.friction > 0.0 && !candidate.friction.sliding;
      ++active;
      continue;
    }
    const Vec3 slip = candidate.relativeVelocity + solver_.solvedRelativeChange(static_cast<int>(k));
    record.sticking = (slip - candidate.normal * candidate.normal.dot(slip)).norm() < candidate.law.frictionVelocity;
    ++active;
  }
  return active;
}

}  // namespace rope::bullet
