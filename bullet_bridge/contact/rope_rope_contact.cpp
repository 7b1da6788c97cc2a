// SPDX-License-Identifier: MIT
#include "bullet_bridge/contact/rope_rope_contact.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include <Eigen/Geometry>

#include "bullet_bridge/contact/contact_response.h"
#include "bullet_bridge/rope_object.h"
#include "bullet_bridge/narrowphase/segment_segment_distance.h"
#include "rope/common/error.h"

namespace rope::bullet {

namespace {

constexpr int kMaxSolvePasses = 6;  // small dense solves: contacts switch on and off, friction bounds settle
constexpr double kFrictionBoundTolerance = 0.05;

btVector3 toBullet(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()), static_cast<btScalar>(v.z()));
}

// Cumulative rest length at the start of every knot span of the rod (span j = knot span degree + j),
// so that the rest arclength between two parameters costs a binary search.
void buildRestArc(const Rod& rod, std::vector<double>& starts) {
  const RodIntegrals& integrals = rod.integrals();
  starts.resize(static_cast<size_t>(integrals.spanCount()) + 1);
  starts[0] = 0.0;
  for (int j = 0; j < integrals.spanCount(); ++j) {
    starts[static_cast<size_t>(j) + 1] = starts[static_cast<size_t>(j)] + integrals.span(j).restLength;
  }
}

// Rest arclength from the rod's start to C(s), linear in s inside a span (exact for ropes made from a
// segment, whose parameter is the rest arclength).
double restArcAt(const Rod& rod, const std::vector<double>& starts, double s) {
  const KnotVector& knots = rod.knots();
  const int k = knots.findSpan(s);
  const int j = k - knots.degree();
  const double width = knots[k + 1] - knots[k];
  const double fraction = width > 0.0 ? (s - knots[k]) / width : 0.0;
  return starts[static_cast<size_t>(j)] + fraction * (starts[static_cast<size_t>(j) + 1] - starts[static_cast<size_t>(j)]);
}

double parameterAt(const CapsuleProxy& proxy, double t) {
  if (t <= 0.0) return proxy.s0;
  if (t >= 1.0) return proxy.s1;  // exactly the neighbour's s0: shared ends give identical contacts
  return std::min(proxy.s1, std::max(proxy.s0, proxy.s0 + t * (proxy.s1 - proxy.s0)));
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
  facts_.resize(ropes.size());
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
    if (proxies.size() == 0) continue;  // no pair can name one of its capsules
    ends.resize(static_cast<size_t>(proxies.size()) + 1);
    for (int i = 0; i <= proxies.size(); ++i) {
      const double s = i < proxies.size() ? proxies.proxy(i).s0 : proxies.proxy(i - 1).s1;
      ends[static_cast<size_t>(i)] = {restArcAt(rod, restArc_[r], s), rod.velocity(s).norm()};
    }
    boxes.resize(static_cast<size_t>(proxies.size()));
    for (int i = 0; i < proxies.size(); ++i) {
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

double RopeRopeContacts::reach(const RopeCapsulePair& pair) const {
  const RopeFacts& a = facts_[static_cast<size_t>(pair.ropeA)];
  const RopeFacts& b = facts_[static_cast<size_t>(pair.ropeB)];
  // Candidates: gaps that the step can close (both ropes' speeds) plus a fraction of the radii; the
  // body margin (speculativeMargin, sized for fast ropes against thin bodies) would flood a knot
  // with distant pairs.
  const double margin = std::min(std::max(a.margin, b.margin), 0.5 * (a.radius + b.radius));
  return margin + h_ * (boxes_[static_cast<size_t>(pair.ropeA)][static_cast<size_t>(pair.capsuleA)].speed +
                        boxes_[static_cast<size_t>(pair.ropeB)][static_cast<size_t>(pair.capsuleB)].speed);
}

bool RopeRopeContacts::mayTouch(const RopeCapsulePair& pair) const {
  const RopeFacts& ropeA = facts_[static_cast<size_t>(pair.ropeA)];
  const RopeFacts& ropeB = facts_[static_cast<size_t>(pair.ropeB)];
  const bool self = pair.ropeA == pair.ropeB;
  if (self && !ropeA.selfContact) return false;
  if (pair.capsuleA >= ropeA.capsules || pair.capsuleB >= ropeB.capsules) return false;
  if (self) {
    // Pairs whose every point pair is excluded (neighbouring capsules, which always overlap).
    const CapsuleEnd* endsA = &ends_[static_cast<size_t>(pair.ropeA)][static_cast<size_t>(pair.capsuleA)];
    const CapsuleEnd* endsB = &ends_[static_cast<size_t>(pair.ropeB)][static_cast<size_t>(pair.capsuleB)];
    if (std::max(std::abs(endsB[1].arc - endsA[0].arc), std::abs(endsA[1].arc - endsB[0].arc)) < ropeA.exclusion)
      return false;
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
  return !(gap2 > limit * limit);
}

void RopeRopeContacts::dropDistantPairs(std::vector<RopeCapsulePair>& pairs) const {
  pairs.erase(std::remove_if(pairs.begin(), pairs.end(), [&](const RopeCapsulePair& pair) { return !mayTouch(pair); }),
              pairs.end());
}

int RopeRopeContacts::solve(const std::vector<RopeObject*>& ropes, const std::vector<RopeCapsulePair>& pairs,
                            double h, std::vector<RopePairContactRecord>& records) {
  candidates_.clear();

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

    const Vec3 pointA = rodA.position(sA);
    const Vec3 pointB = rodB.position(sB);
    Vec3 normal = pointA - pointB;
    double centres = normal.norm();
    if (centres > 1e-12 * radii) {
      normal /= centres;
    } else {
      // Centre lines meet: separate across both tangents (or any direction normal to A's).
      normal = rodA.tangent(sA).cross(rodB.tangent(sB));
      if (!(normal.norm() > 1e-9)) normal = rodA.tangent(sA).unitOrthogonal();
      normal.normalize();
      centres = 0.0;
    }
    Candidate candidate;
    candidate.record = -1;
    candidate.ropeA = pair.ropeA;
    candidate.ropeB = pair.ropeB;
    candidate.sA = sA;
    candidate.sB = sB;
    candidate.arcA = arcSA;
    candidate.arcB = arcSB;
    candidate.spacing = radii;
    candidate.distance = centres - radii;
    candidate.normal = normal;
    candidate.frictionNormalForce = -1.0;
    candidate.active = false;
    // law, relativeVelocity and coupled: for the kept candidates only, after the thinning.
    candidate.relativeVelocity = Vec3::Zero();
    candidate.coupled = false;
    candidates_.push_back(candidate);
  }

  // One contact per place: neighbouring capsule pairs find the same crossing (or the same stretch of a
  // side-by-side contact) several times. Deepest first; a candidate within one contact spacing (the sum
  // of the radii, along both rest curves) of an accepted one is dropped, so a line contact is sampled
  // about once per diameter.
  // Sorted through small keys (a knot has about 900 candidates of some 200 bytes each). Candidates
  // with equal keys are the same contact found twice (one point, the same everything), so their
  // order does not matter.
  sortKeys_.clear();
  for (size_t c = 0; c < candidates_.size(); ++c) {
    const Candidate& k = candidates_[c];
    sortKeys_.push_back({k.distance, k.ropeA, k.sA, k.ropeB, k.sB, static_cast<int>(c)});
  }
  std::sort(sortKeys_.begin(), sortKeys_.end(), [](const SortKey& a, const SortKey& b) {
    return std::tie(a.distance, a.ropeA, a.sA, a.ropeB, a.sB) < std::tie(b.distance, b.ropeA, b.sA, b.ropeB, b.sB);
  });
  sorted_.clear();
  for (const SortKey& key : sortKeys_) sorted_.push_back(candidates_[static_cast<size_t>(key.index)]);
  candidates_.swap(sorted_);
  // The accepted ones are also kept ordered by (ropeA, ropeB, arcA), so each test looks only at those
  // within one spacing along A: O(c log c) instead of comparing every candidate with every accepted
  // one (a tight knot has hundreds of candidates).
  const auto byArc = [this](int x, double arc, int ropeA, int ropeB) {
    const Candidate& k = candidates_[static_cast<size_t>(x)];
    return std::tie(k.ropeA, k.ropeB, k.arcA) < std::tie(ropeA, ropeB, arc);
  };
  keptByArc_.clear();
  size_t kept = 0;
  for (size_t c = 0; c < candidates_.size(); ++c) {
    const Candidate candidate = candidates_[c];
    auto it = std::lower_bound(keptByArc_.begin(), keptByArc_.end(), candidate.arcA - candidate.spacing,
                               [&](int x, double arc) { return byArc(x, arc, candidate.ropeA, candidate.ropeB); });
    bool near = false;
    for (; it != keptByArc_.end() && !near; ++it) {
      const Candidate& other = candidates_[static_cast<size_t>(*it)];
      if (other.ropeA != candidate.ropeA || other.ropeB != candidate.ropeB || !(other.arcA < candidate.arcA + candidate.spacing))
        break;
      near = std::abs(other.arcA - candidate.arcA) < candidate.spacing &&
             std::abs(other.arcB - candidate.arcB) < candidate.spacing;
    }
    if (near) continue;
    candidates_[kept] = candidate;
    const auto at = std::upper_bound(keptByArc_.begin(), keptByArc_.end(), static_cast<int>(kept),
                                     [this](int x, int y) {
                                       const Candidate& a = candidates_[static_cast<size_t>(x)];
                                       const Candidate& b = candidates_[static_cast<size_t>(y)];
                                       return std::tie(a.ropeA, a.ropeB, a.arcA) < std::tie(b.ropeA, b.ropeB, b.arcA);
                                     });
    keptByArc_.insert(at, static_cast<int>(kept));
    ++kept;
  }
  candidates_.resize(kept);
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
    candidate.relativeVelocity = ropeA.rod().velocity(candidate.sA) - ropeB.rod().velocity(candidate.sB);
    candidate.coupled = ropeA.rod().hasTrial() && ropeB.rod().hasTrial();
  }
  for (Candidate& candidate : candidates_) {
    const RopeObject& ropeA = *ropes[static_cast<size_t>(candidate.ropeA)];
    const RopeObject& ropeB = *ropes[static_cast<size_t>(candidate.ropeB)];
    RopePairContactRecord record;
    record.ropeA = &ropeA;
    record.ropeB = &ropeB;
    record.sA = candidate.sA;
    record.sB = candidate.sB;
    record.pointA = toBullet(ropeA.rod().position(candidate.sA));
    record.pointB = toBullet(ropeB.rod().position(candidate.sB));
    record.normal = toBullet(candidate.normal);
    record.depth = -candidate.distance;
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
                          rodIndex[static_cast<size_t>(candidate.ropeB)], candidate.sB});
    coupled_.push_back(static_cast<int>(c));
  }
  if (couplings_.empty()) return 0;

  solver_.prepare(rods_, couplings_);
  const auto lawOf = [h](const Candidate& candidate) {
    CouplingLaw law;
    if (!candidate.active) return law;
    // The contact law in the relative velocity (the "body" at rest in B's frame): f0, K, D.
    const ContactSpring spring = contactSpring(candidate.law, candidate.distance, candidate.normal,
                                               candidate.relativeVelocity, Vec3::Zero(), h,
                                               candidate.frictionNormalForce);
    law.impulse = h * (spring.force - h * (spring.stiffness * candidate.relativeVelocity));
    law.admittance = h * h * spring.stiffness + h * spring.damping;
    return law;
  };
  laws_.resize(couplings_.size());
  for (size_t k = 0; k < couplings_.size(); ++k) laws_[k] = lawOf(candidates_[static_cast<size_t>(coupled_[k])]);

  bool solved = false;
  for (int pass = 1; pass <= kMaxSolvePasses; ++pass) {
    solved = solver_.solveImpulses(laws_, impulses_);
    if (!solved || pass == kMaxSolvePasses) break;
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
      laws_[k] = lawOf(candidate);
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

  int active = 0;
  for (size_t k = 0; k < couplings_.size(); ++k) {
    const Candidate& candidate = candidates_[static_cast<size_t>(coupled_[k])];
    if (!candidate.active) continue;
    RopePairContactRecord& record = records[static_cast<size_t>(candidate.record)];
    record.active = true;
    record.force = toBullet(impulses_[k] / h);
    const Vec3 slip = candidate.relativeVelocity + solver_.solvedRelativeChange(static_cast<int>(k));
    record.sticking = (slip - candidate.normal * candidate.normal.dot(slip)).norm() < candidate.law.frictionVelocity;
    ++active;
  }
  return active;
}

}  // namespace rope::bullet
