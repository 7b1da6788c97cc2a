// SPDX-License-Identifier: MIT
#pragma once
// Contact between ropes and of a rope with itself ([A] §5.2 knot tying needs the rope to stay out of
// itself). Candidates are the pairs of rope capsules that Bullet's broadphase reports (RopeWorld
// reads them from the pair cache with the rope-body pairs). For each pair the capsule axes' closest
// points (narrowphase/segment_segment_distance.h) give curve parameters sA, sB; the contact is evaluated on the
// curve itself, d = |C_A(sA) - C_B(sB)| - (r_A + r_B), n = (C_A - C_B)/|C_A - C_B|.
//
// Response: the same penalty law with damping, speculative approach and regularised Coulomb friction
// as rope-body contact (contact_response.h), written in the relative velocity w = C'_A(sA) - C'_B(sB),
// and coupled implicitly into both ropes' steps at once by rope::CoupledSolve (the ropes' factors get
// a low-rank correction; no band is broken, nothing is lagged). The impulses are equal and opposite, so
// rope-rope contact conserves momentum to round-off. As for bodies, contact is unilateral and friction
// bounded by the actual normal force: contacts that come out pulling are released, contacts the solve
// predicts to end the step overlapping are switched on, and friction bounds are re-estimated from the
// end-of-step normal force, at most 6 small solves per substep (12 with distributed samples, below;
// the ropes' factors are reused).
//
// Distributed contact (docs/method.md §12, eqs. 37a-b): where two *different* ropes touch along a
// stretch at least one contact spacing (r_A + r_B) long (a rope wrapped round a taut one, or lying
// along another), the point contacts there are replaced by Gauss-Legendre samples along the touching
// stretch of the rope that curves round the other, per chunk of half a contact spacing of its rest
// arclength (so their number follows the length in contact, not the resolution), each projected
// onto the other curve, with the point law per contact spacing times the rest length it stands for,
// and rope-body samples' friction: a sticking spring whose stretch is carried along the sampled rope
// (rope_stick_memory.h), or exactly mu f_n when sliding. Point contacts with regularised friction could not hold a rope round a
// taut rope (crept at 7-103 mm/s at 0.9 of the capstan limit: 3-4 contacts that jumped along the wrap
// from substep to substep); the samples hold it to 2e-7 m/s. Crossings (shorter stretches) and
// self-contact stay point contacts (docs/method.md §12 says what distributed self-contact did to the
// knot and the pile). Samples are not interaction points (no knot each).
//
// Excluded: two points of one rope closer than BulletRopeSettings::selfContactExclusion along the rest
// curve (neighbouring capsules always overlap; that is the rope, not a contact), the same across the
// cut of two pieces cut from one rope (RopeObject::cut), and ropes with selfContact off. Point
// contacts become interaction knots ([A] §4), so the rope refines where it presses on itself.
// Not API: installed only because rope_world.h holds the solver; it may change in any release.

#include <algorithm>
#include <cstddef>
#include <vector>

#include "bullet_bridge/contact_report.h"
#include "bullet_bridge/contact/contact_response.h"
#include "bullet_bridge/contact/rope_stick_memory.h"
#include "bullet_bridge/detail/radix_sort.h"
#include "bullet_bridge/friction_combination.h"
#include "rope/rod/coupled_solve.h"
#include "rope/spline/bspline_curve.h"

namespace rope::bullet {

class RopeObject;

// A broadphase pair of rope capsules, ordered: ropeA < ropeB, or capsuleA < capsuleB on one rope.
struct RopeCapsulePair {
  int ropeA = 0;     // indices into the ropes given to RopeRopeContacts::solve
  int capsuleA = 0;
  int ropeB = 0;
  int capsuleB = 0;
};

class RopeRopeContacts {
 public:
  // Once per substep, before the two calls below, with the ropes' capsules current (after their
  // beginSubstep): the rest arclength and speed at every capsule end and every capsule axis's box,
  // at the ropes' state before the step. h: the substep, s.
  void prepare(const std::vector<RopeObject*>& ropes, double h);
  // Removes the pairs that cannot touch within the step, keeping the order of the rest: a capsule
  // index out of range, a self-pair whose every point pair is excluded, axes' boxes further apart
  // than the radii and the distance the step can close. Cheap (no curve evaluation), so that the
  // caller's sort and solve() see only the near pairs (in a tight knot about 1 in 7 of the tree's).
  void dropDistantPairs(std::vector<RopeCapsulePair>& pairs) const;
  // After prepare() and dropDistantPairs() with the same ropes and h.
  // Finds the contacts of the candidate pairs (sorted by the caller for determinism) at the ropes'
  // state before the step, solves them together with the ropes' trial steps (RopeObject::beginSubstep
  // left one on every rope whose step succeeded; contacts with a failed rope are skipped) and corrects
  // the trials. Appends one record per contact found and returns the number of active ones, or -1 if
  // the coupled solve failed numerically (the ropes then keep their uncoupled trials and every
  // contact is reported inactive).
  int solve(const std::vector<RopeObject*>& ropes, const std::vector<RopeCapsulePair>& pairs, double h,
            std::vector<RopePairContactRecord>& records);
  // solve() in two halves. detect() finds the contacts: it reads only the ropes' capsules and their
  // rods' state before the step (not their trials, loads or records) and calls no user code, so it
  // may run on another thread while the ropes' trials are solved (rope_world.cpp). respond() then
  // records them and solves them with the trials, as solve() does.
  void detect(const std::vector<RopeObject*>& ropes, const std::vector<RopeCapsulePair>& pairs);
  int respond(const std::vector<RopeObject*>& ropes, double h, std::vector<RopePairContactRecord>& records);
  // m: the part of two ropes' speculative margins (BulletRopeSettings::speculativeMargin, m) a pair's
  // candidates reach beyond the radii (r, m) before the step's travel: the larger margin, at most half
  // the radii's sum (the body margin, sized for fast ropes against thin bodies, would flood a knot
  // with distant pairs). Shared with the self-contact walk (rope_world.cpp), whose boxes must cover it.
  static double pairMargin(double marginA, double radiusA, double marginB, double radiusB) {
    return std::min(std::max(marginA, marginB), 0.5 * (radiusA + radiusB));
  }
  // Replaces the product of the two ropes' coefficients (friction_combination.h); empty: the product.
  void setFrictionCombiner(RopeFrictionCombiner combiner) { combiner_ = std::move(combiner); }
  // Lets go of the stick state of one rope's distributed contacts, or of all: a rope that leaves the
  // world or is cut, a solve that failed. The state names ropes by address, so a removed rope must be
  // forgotten before it can be destroyed.
  void forget(const RopeObject& rope) { memory_.forget(rope); }
  void forgetAll() { memory_.clear(); }

 private:
  struct Candidate {
    int record;          // index into the records
    int ropeA, ropeB;
    double sA, sB;
    double arcA, arcB;   // rest arclength of sA, sB, m
    double spacing;      // m of rest length: closer candidates are the same contact
    bool coupled;        // both ropes have a trial (else the contact is only reported)
    ContactLaw law;
    double distance;     // m, < 0 overlapping
    Vec3 normal;         // from B into A
    Vec3 relativeVelocity;  // w = C'_A(sA) - C'_B(sB) before the step
    double frictionNormalForce;  // N, < 0: the start-of-step estimate
    bool active;
    bool suppressed = false;  // a point contact inside a distributed contact (its samples carry it)
    bool sample = false;      // a quadrature sample of a distributed contact (A is the sampled rope)
    double weight = 0.0;      // sample: m of rest length of A it stands for
    SampleFriction friction;  // sample: sticking (its spring's stretch) or sliding
    int spanA = -1, spanB = -1;  // knot spans of sA, sB where known (hints for curvePositionNear)
  };
  // Where the axis of one capsule (the sampled one) touches another's (see the header comment).
  struct Stretch {
    int sampledRope = 0, sampledCapsule = 0;
    int otherRope = 0, otherCapsule = 0;
    double lo = 0.0, hi = 0.0;        // along the sampled capsule's axis, [0, 1]
    double arcLo = 0.0, arcHi = 0.0;  // the same as rest arclength of the sampled rope, m
    double reach = 0.0;               // m: the pair's reach
    int candidate = -1;               // the pair's point contact
  };
  std::vector<Stretch> stretches_;
  std::vector<Candidate> samples_;
  RopeStickMemory memory_;
  std::vector<std::vector<Vec3>> bends_;  // per rope: curvature vector of each capsule, 1/m
  std::vector<Candidate> candidates_;
  // A capsule pair within reach, before the thinning: its axes' closest points as curve parameters.
  struct Hit {  // 64 bytes: the doubles first, no padding between the ints
    double gap;         // m, < 0 overlapping: on the curve once evaluated (candidate >= 0), else a lower bound
    double sA, sB;
    double arcA, arcB;  // rest arclength of sA, sB, m
    int ropeA, ropeB;
    int candidate;      // its point contact in candidates_ once evaluated (two ropes: at once), else -1
    int spanA, spanB;   // knot spans of the capsules' starts: hints for sA's and sB's span searches
  };
  // m of rest length: hits of two ropes closer than this are the same contact (the radii's sum).
  double spacing(int ropeA, int ropeB) const {
    return facts_[static_cast<std::size_t>(ropeA)].radius + facts_[static_cast<std::size_t>(ropeB)].radius;
  }
  std::vector<Hit> hits_;
  std::vector<KeyedIndex> order_;  // the hits to thin (gap, index into hits_), by (gap, ropeA, sA, ropeB, sB)
  std::vector<KeyedIndex> orderScratch_;
  std::vector<int> waiting_;    // evaluated hits not yet accepted or dropped: a heap, during the thinning
  struct Accepted {
    int ropeA, ropeB;
    double arcA, arcB;  // m of rest length
  };
  std::vector<Accepted> keptByArc_;  // the accepted hits by (ropeA, ropeB, arcA), during the thinning
  std::vector<Candidate> kept_;
  std::vector<CurvePoint> endCurve_;  // scratch of boundAxisDeparture: the curve at each capsule end
  // Per rope (empty until a self-contact hit needs it) and capsule: bound of the axis's departure from
  // the curve, m; per rope: bound of the rounding of a distance of axis points, m.
  std::vector<std::vector<double>> deviation_;
  std::vector<double> roundoff_;
  std::vector<PointCoupling> couplings_;
  std::vector<CouplingLaw> laws_;
  std::vector<int> coupled_;  // candidate index of each coupling
  std::vector<Vec3> impulses_;
  std::vector<Rod*> rods_;
  std::vector<int> rodIndex_;  // per rope: its rod's index in rods_, -1 without a trial
  std::vector<std::vector<double>> restArc_;  // per rope: cumulative rest length at each span start
  struct CapsuleEnd {
    double arc;    // rest arclength, m
    double speed;  // m/s before the step
  };
  std::vector<std::vector<CapsuleEnd>> ends_;  // per rope: capsule ends (capsule i spans i, i + 1)
  struct AxisBox {
    double low[3], high[3];  // m, world frame
    double speed;            // m/s: the faster of the capsule's ends before the step
  };
  std::vector<std::vector<AxisBox>> boxes_;  // per rope: the box of each capsule's axis
  std::vector<std::vector<int>> capsuleSpans_;  // per rope: the knot span of each capsule's start
  // What the pair tests read of each rope, once per substep.
  struct RopeFacts {
    double radius;     // m
    double margin;     // speculativeMargin, m
    double exclusion;  // self-contact exclusion along the rest curve, m
    bool selfContact;
    int capsules;
  };
  std::vector<RopeFacts> facts_;
  double h_ = 0.0;  // the substep prepare() was called for, s
  // m: the gap the pair's step may close (speculative margin and both capsules' speeds).
  // Defined here, inline: mayTouch asks it for every pair the walk reports.
  double reach(const RopeCapsulePair& pair) const {
    const RopeFacts& a = facts_[static_cast<std::size_t>(pair.ropeA)];
    const RopeFacts& b = facts_[static_cast<std::size_t>(pair.ropeB)];
    // Candidates: gaps that the step can close (both ropes' speeds) plus part of the margins.
    const double margin = pairMargin(a.margin, a.radius, b.margin, b.radius);
    return margin + h_ * (boxes_[static_cast<std::size_t>(pair.ropeA)][static_cast<std::size_t>(pair.capsuleA)].speed +
                          boxes_[static_cast<std::size_t>(pair.ropeB)][static_cast<std::size_t>(pair.capsuleB)].speed);
  }
  bool mayTouch(const RopeCapsulePair& pair) const;
  // A contact of C_A(sA) with C_B(sB), centres m apart along normal (from B into A), not yet acting.
  static Candidate contactBetween(int ropeA, double sA, double arcA, int ropeB, double sB, double arcB, double radii,
                                  double centres, const Vec3& normal);
  // The point contact of a hit, on the curves at the ropes' state before the step; centresOut (if
  // given): the distance of the curve points, m.
  static Candidate pointContact(const Rod& rodA, const Rod& rodB, const Hit& hit, double spacing,
                                double* centresOut = nullptr);
  void addTouchingStretch(const std::vector<RopeObject*>& ropes, const RopeCapsulePair& pair, double closestS,
                          double closestT, double closestDistance, const Vec3& normal, double centres, int candidate);
  void sampleDistributedContacts(const std::vector<RopeObject*>& ropes);
  void sampleRegion(const std::vector<RopeObject*>& ropes, size_t first, size_t last);
  // Gauss-Legendre nodes on [s0, s1] of the sampled rope, each projected onto the nearest of the other
  // rope's capsules that stretches [first, last) name.
  void sampleRun(const std::vector<RopeObject*>& ropes, size_t first, size_t last, double s0, double s1);
  void startSample(const RopeObject& sampled, const RopeObject& other, Candidate& candidate) const;
  CouplingLaw lawOf(const Candidate& candidate, double h) const;
  bool updateSampleFriction(Candidate& candidate, int k, double normalForce, double h);
  void rememberSampleFriction(const std::vector<RopeObject*>& ropes, double h);
  CoupledSolve solver_;
  RopeFrictionCombiner combiner_;
};

}  // namespace rope::bullet
