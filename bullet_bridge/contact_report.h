// SPDX-License-Identifier: MIT
#pragma once
// What the ropes of a world did in one Bullet substep, for users' own checks (e.g. CI tests that a
// rope never sinks into a body): every contact with its force and friction state, and per rope the
// deepest penetration and the health of its step.

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <LinearMath/btVector3.h>

#include <vector>

#include "bullet_bridge/bullet_precision.h"

namespace rope::bullet {

class RopeObject;

struct RopeContactRecord {
  const RopeObject* rope = nullptr;
  const btCollisionObject* body = nullptr;
  double s = 0.0;                  // curve parameter of the contact on the rope
  btVector3 point{0, 0, 0};        // on the body surface, world frame, m (start of the substep)
  btVector3 normal{0, 0, 1};       // unit, from the body into the rope
  double depth = 0.0;              // penetration, m (> 0 penetrating, < 0 speculative gap)
  btVector3 force{0, 0, 0};        // force on the rope over the substep, N (the body got -force * h)
  bool sticking = false;           // tangential slip below the friction regularisation velocity
  bool active = false;             // false: a speculative contact that did not act in this substep
};

// One contact between two ropes, or between two parts of one rope (self-contact): capsules whose axes
// came closer than the sum of the radii (plus the speculative margin), coupled implicitly in the
// ropes' step (contact/rope_rope_contact.h).
struct RopePairContactRecord {
  const RopeObject* ropeA = nullptr;
  const RopeObject* ropeB = nullptr;  // == ropeA for self-contact
  double sA = 0.0;                    // curve parameters of the contact points
  double sB = 0.0;
  btVector3 pointA{0, 0, 0};          // C_A(sA), C_B(sB) at the start of the substep, world frame, m
  btVector3 pointB{0, 0, 0};
  btVector3 normal{0, 0, 1};          // unit, from B into A
  double depth = 0.0;                 // overlap of the two tubes, m (> 0 overlapping, < 0 speculative gap)
  btVector3 force{0, 0, 0};           // force on A over the substep, N (B felt -force)
  bool sticking = false;              // tangential slip below the friction regularisation velocity
  bool active = false;                // false: a speculative contact that did not act, or was released
  // A point contact (a crossing, self-contact): 0. A sample of a distributed contact between two ropes
  // (one wrapped round or lying along the other; A is the sampled rope): the rest length of A it stands
  // for, m, so that force / weight is the line load there, N/m.
  double weight = 0.0;
};

// The load at one attachment of a rope after a substep (RopeObject::attachments()).
struct RopeAttachmentRecord {
  const RopeObject* rope = nullptr;
  int id = 0;                             // the attachment's id
  double s = 0.0;                         // where on the rope
  const btCollisionObject* body = nullptr;  // nullptr: a point attachment (pin)
  btVector3 force{0, 0, 0};               // body attachments: force on the rope over the substep, N
  double tension = 0.0;                   // axial force in the rope at s, N (RopeObject::tension)
};

struct RopeStepRecord {
  const RopeObject* rope = nullptr;
  bool ok = true;                // false: the rod step failed and the rope kept its state
  const char* failure = "";      // why (static text)
  bool resting = false;          // the rope is at rest: frozen, still colliding (RopeObject::kFailuresBeforeRest)
  double maxPenetration = 0.0;   // m, deepest contact at the start of the substep (0 if none)
  int contacts = 0;              // active contacts
  int proxyOverflows = 0;        // capsules whose box was too large for Bullet (not updated)
  int skippedBodies = 0;         // candidate or attached bodies skipped (non-finite state, unsupported shape)
  int droppedAttachments = 0;    // body attachments dropped because their body left the Bullet world
  int controlPoints = 0;         // after the step's adaptivity
  int insertions = 0;            // knots inserted by the step's adaptivity
  int removals = 0;              // knots removed by the step's adaptivity
  // StepReport's: m, largest move by which an insertion gave back revealed stretching energy (free
  // ropes), and J, revealed energy an insertion did not give back (rope/rod/rod.h).
  double maxInsertionRelaxation = 0.0;
  double unrelaxedInsertionEnergy = 0.0;
  int solvePasses = 0;           // rod solves in the substep (contact active set, contact/contact_response.h)
  // After the active set, the kept trial was solved once more with the rod's stretching relinearised
  // about it (Rod::trialNeedsRelinearisation: its one-pass step made more stretching energy than 1 %
  // of the energy in play; rope_object.cpp, solveTrialWithContacts). Not counted in solvePasses.
  bool contactRelinearised = false;
  // The active set had not settled when its last pass was kept (RopeObject::kMaxContactSolvePasses):
  // some contact of the kept trial pulls, sticks beyond mu f_n, or slides on a bound 5 % off its
  // normal force. A quality warning, not a failure (RopeWarnings::unsettledContactSteps counts it).
  bool contactsUnsettled = false;
  int ropeContacts = 0;          // active rope-rope and self-contacts this rope takes part in
  double maxSelfOverlap = 0.0;   // m, deepest overlap with itself or another rope at the start of the substep
  // Wall-clock time of the rope's parts of the substep, s (profiling only; not deterministic).
  double contactSeconds = 0.0;   // candidate recheck, narrowphase and contact law
  double solveSeconds = 0.0;     // rod step (implicit solve, adaptivity) and body impulses
  double proxySeconds = 0.0;     // capsule rebuild, tree leaves refitted, rope box to the broadphase
};

struct ContactReport {
  long substep = 0;     // substeps run since the RopeWorld was created (1 for the first)
  double timeStep = 0;  // s
  // Non-empty: the whole substep was skipped (a time step that is not finite and > 0) or failed at
  // world level; the ropes kept their state (static text; RopeWorld::warnings() counts it).
  const char* failure = "";
  std::vector<RopeContactRecord> contacts;
  std::vector<RopeStepRecord> ropes;
  std::vector<RopePairContactRecord> ropeContacts;  // rope-rope and self-contacts
  std::vector<RopeAttachmentRecord> attachments;    // every attachment of every rope, after the substep
  double ropeContactSeconds = 0.0;  // rope-rope narrowphase and coupled solve, s (profiling)
  const char* ropeContactFailure = "";  // non-empty: the rope-rope solve failed this substep (static text)
  double pairScanSeconds = 0.0;  // midphase: the dispatched rope pairs and the ropes' trees, s (profiling)
  // The rope-rope and self-contact detection ran on the RopeWorld's side thread, beside the ropes'
  // body contacts and trials (RopeWorld::setParallelContactDetection); the results are the same.
  bool detectedOnSideThread = false;
  double maxPenetration() const;  // over all ropes, m
  double maxSelfOverlap() const;  // over all rope-rope and self-contacts, m
};

}  // namespace rope::bullet
