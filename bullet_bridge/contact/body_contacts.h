// SPDX-License-Identifier: MIT
#pragma once
// Rope-body contact of one rope in one substep, as a line load (line_contact.h) with sticking
// friction (contact_response.h: sampleSpring; friction_anchors.h):
//   gather()  finds the touching stretches of the rope's capsules against the candidate bodies, their
//             quadrature samples, and each sample's law and friction state at the rod's current state;
//   queue()   puts the active samples' springs on the rod (Rod::addSpringSample: no knots);
//   update()  after a trial step, makes contact unilateral and friction Coulomb's: gives sliding
//             samples the friction bound mu f_n of the normal force they end the step with (solved
//             exactly, with the trial corrected, where the bounds are strongly coupled, on bodies at
//             rest and on a rope that touched no rope last substep: docs/method.md §11; otherwise
//             re-bounded pass by pass), releases samples whose end-of-step normal force
//             pulls, switches sticking samples whose spring needs more than mu f_n to sliding, and
//             re-bounds sliding friction where the normal force still moved by more than 5 %; true
//             if the trial must be solved again;
//   finish()  after the final trial: the equal and opposite impulse on every dynamic body, the
//             records, the anchors for the next substep, the knots the contact geometry needs, and
//             caps on the coming knot removals where friction holds a load (Rod::limitShapeChange).
//
// Adaptivity follows geometry, not touch: a rope lying along a surface asks for no knot (its
// samples are not interaction points). A touching stretch much shorter than the knot span around it
// (BulletRopeSettings::concentratedContactRatio: a thin bar, an edge) is a concentrated load, which a
// C2 cubic can only carry by kinking at a knot, so its centre is marked as an interaction (a knot
// there, kept while the load lasts). Wrapping round a curved body bends the control polygon, which
// the rod's own curvature criterion refines.
//
// Dynamic bodies get the samples' forces as explicit impulses, so the sum of the samples' stiffness
// (and damping) on one body is capped at bodyStabilityFactor * m_eff / h^2 (/ h), m_eff the smallest
// effective mass along the normals at its contact points.
//
// Not API: installed only because rope_object.h includes it; may change in any release.

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <functional>

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/capsule_proxies.h"
#include "bullet_bridge/contact_report.h"
#include "bullet_bridge/contact/contact_response.h"
#include "bullet_bridge/contact/friction_anchors.h"
#include "bullet_bridge/contact/line_contact.h"
#include "bullet_bridge/rope_settings.h"
#include "rope/common/gmres.h"
#include "rope/rod/rod.h"

namespace rope::bullet {

class BodyContacts {
 public:
  // Whether contacts of the rope piece [s0, s1] with object are ignored (an attachment sits there).
  using Exclusion = std::function<bool(const btCollisionObject& object, double s0, double s1)>;
  // The combined friction coefficient of the rope with object (friction_combination.h).
  using FrictionOf = std::function<double(const btCollisionObject& object)>;

  // Finds the samples and evaluates their laws; fills records (one per sample, active or not) and
  // step.maxPenetration / contacts / skippedBodies.
  void gather(const Rod& rod, const CapsuleProxies& proxies, const std::vector<const btCollisionObject*>& candidates,
              const BulletRopeSettings& settings, const Exclusion& excluded, const FrictionOf& friction, double h,
              std::vector<RopeContactRecord>& records, RopeStepRecord& step);
  void queue(Rod& rod) const;
  // Whether update() may solve strongly coupled sliding bounds exactly (solveSlidingBounds); default on.
  void setExactBounds(bool exact) { exactBounds_ = exact; }
  bool update(Rod& rod, double h, std::vector<RopeContactRecord>& records, RopeStepRecord& step);
  // Whether update() would change nothing for the current trial (without re-solving the sliding
  // bounds): the active set has settled. For the last pass, which is kept without an update().
  bool settled(const Rod& rod, double h) const;
  void finish(Rod& rod, double h, double concentratedContactRatio, std::vector<RopeContactRecord>& records);
  // Forgets the samples of this substep (the anchors stay) / everything.
  void dropSamples() { samples_.clear(); }
  void reset();
  int anchorCount() const { return anchors_.size(); }
  // Whether a sample of this substep is on a dynamic body (finish() may give that body an impulse).
  bool pushesBodies() const;
  // Cache hints (rope/common/prefetch.h) for the samples and anchors the next substep reads.
  void prefetch() const;

  // The samples' storage and gather()'s working lists, which a caller may lend for one substep:
  // swapScratch before gather() and again after finish() (the samples each side receives are
  // emptied; what it held is scratch).
  // RopeWorld lends one set to every rope it finishes within its own visit, so the samples are
  // written where the rope before wrote its own, still in the caches, and not into each rope's, which
  // a thousand ropes push out of them (a fifth of a resting rope's memory traffic per step).
  class Scratch;
  void swapScratch(Scratch& scratch);

 private:
  // What update() does with one active sample after a trial.
  enum class Change { kNone, kRelease, kSlide, kRebound };
  struct Sample {
    ContactSample geometry;
    btRigidBody* body = nullptr;                // receives the opposite impulse (nullptr: static, kinematic)
    const btCollisionObject* object = nullptr;
    Vec3 normal = Vec3::Zero();
    Vec3 ropeVelocity = Vec3::Zero();           // u(s) before the step
    Vec3 bodyVelocity = Vec3::Zero();           // of the body point before the step
    ContactLaw law;                             // weighted: N/m, N s/m
    SampleFriction friction;
    double pressureEstimate = -1.0;             // N/m from the stored anchors, < 0: none
    // The surface's curvature along the rope (springOf): the unit rope tangent in the contact's
    // tangent plane, and how fast the normal turns along it, 1/m (> 0 convex, < 0 concave).
    Vec3 along = Vec3::Zero();
    double curvature = 0.0;
    double geometricLimit = 0.0;                // N/m: cap on the turning normal's stiffness
    ContactSpring spring;
    bool active = false;
    int record = -1;
    // The basis at geometry.s on the knots of the substep, which stay until the trial is committed:
    // every pass reads the trial's velocity there (curveAt), so the span search and basis are done
    // once per sample instead of once per pass.
    int first = 0;     // first control point with b_i(s) != 0
    int count = 0;     // degree + 1
    double basis[kMaxDegree + 1] = {};
  };
  // sum_i b_i(s) field_i at the sample: curvePosition's sum in its order, so the same bits as
  // rod.velocity(s) or rod.trialVelocity(s) for the rod's velocities or trial velocities.
  static Vec3 curveAt(const Sample& sample, const PointList& field);
  void gatherBody(const Rod& rod, const CapsuleProxies& proxies, const btCollisionObject& object,
                  const BulletRopeSettings& settings, const Exclusion& excluded, const FrictionOf& friction, double h,
                  RopeStepRecord& step);
  // Solves the sliding samples' friction bounds f = f_n(f) exactly for the current trial (see the
  // .cpp) and corrects the trial by the change; false if there was nothing to solve or the solve did
  // not converge (the trial is then unchanged).
  bool solveSlidingBounds(Rod& rod, double h);
  // The change for `sample` at the current trial, with its end-of-step velocity, normal force and
  // (sticking samples) tangential force, which update() uses to apply it.
  static Change changeFor(const Sample& sample, const Rod& rod, double h, Vec3& uNew, double& normalForce,
                          Vec3& tangentForce);
  // Its pieces: each sliding sample's basis, impulse per unit bound, normal-force gradient and
  // right-hand side; the trial's change correction_ = R J(delta); and (M delta)_j from it.
  void gatherSlidingTerms(const Rod& rod, double h);
  void respondToBoundChange(const Rod& rod, const double* delta);
  double normalForceChange(int j) const;
  void capBodies(double h, double share);
  // The sample's spring (sampleSpring) with the normal turning and the gap opening as the rope
  // slides over a curved surface (see the .cpp).
  static ContactSpring springOf(const Sample& sample, double h);
  // Where the body receives a sample's impulse: its body point moved on with the rope's slide.
  static btVector3 bodyPointAfter(const Sample& sample, const Vec3& slip, double radius, double h);
  void markConcentratedLoads(Rod& rod, double ratio) const;
  // Caps the knot removals of the coming commit near a sample that holds a load by friction (its
  // end-of-step force `force`, N): Rod::limitShapeChange.
  static void limitShapeChangeWhereFrictionHolds(Rod& rod, double s, const Vec3& force, const Sample& sample);

  LineContactSampler sampler_;
  std::vector<ContactSample> scratch_;
  Contact probe_;  // gatherBody's curvature probe
  std::vector<Contact> chordContacts_;
  std::vector<int> nearCapsules_;  // gatherBody's midphase result
  btNodeStack treeStack_;          // and its traversal stack
  std::vector<Sample> samples_;
  FrictionAnchors anchors_;
  // solveSlidingBounds' workspace: the sliding samples; per sample its first control point, basis
  // values, impulse per unit bound (-mu h d, N s/N) and normal force's gradient g (N s/m); the
  // right-hand side and the bounds' change (N); the trial's change (3n, m/s).
  bool exactBounds_ = true;
  std::vector<int> sliding_;
  std::vector<int> slidingFirst_;
  std::vector<double> slidingBasis_;
  std::vector<Vec3> slidingPull_;
  std::vector<Vec3> slidingGradient_;
  std::vector<double> boundRhs_;
  std::vector<double> boundDelta_;
  std::vector<double> correction_;
  GmresSolver gmres_;
};

class BodyContacts::Scratch {
  friend class BodyContacts;
  std::vector<Sample> samples;
  LineContactSampler sampler;
  std::vector<ContactSample> sampled;
  std::vector<Contact> chordContacts;
  std::vector<int> nearCapsules;
};

inline void BodyContacts::swapScratch(Scratch& scratch) {
  samples_.swap(scratch.samples);
  samples_.clear();
  scratch.samples.clear();
  // gather() fills these afresh for every body and capsule.
  std::swap(sampler_, scratch.sampler);
  scratch_.swap(scratch.sampled);
  chordContacts_.swap(scratch.chordContacts);
  nearCapsules_.swap(scratch.nearCapsules);
}

}  // namespace rope::bullet
