// SPDX-License-Identifier: MIT
#pragma once
// Where a rope touches a body along one capsule piece, and the quadrature samples that integrate the
// contact pressure over that stretch of the curve (docs/method.md §11, eq. 30).
//
// The contact between a rope and a body is a pressure p(s) along the part of the curve that touches,
// not a force at one parameter. Its consistent generalised force on control point i is
// F_i = integral b_i(s) p(s) dl0 over the touching stretch (dl0 = rest length), and the rope's implicit
// step needs that integral and its stiffness. We integrate it per capsule piece [s0, s1] (a quarter of
// a knot span by default) with an n-point Gauss-Legendre rule on the piece's *touching stretch*
// [a, b] only, not on the whole piece:
//  * where the rope lies along a surface the stretch is the whole piece and the integrand b_i p is
//    smooth, so Gauss-Legendre is the most accurate rule per evaluation (2 points: exact for a cubic
//    b_i times a linear pressure);
//  * where the rope crosses a bar or an edge the touching stretch is far shorter than the piece; a
//    rule over the whole piece would miss it between its nodes (the rope would pass a 2 mm bar), so the
//    stretch's ends are found first (the ball of the rope's radius at C(s) tested against the body,
//    bisected between a touching and a free parameter) and the nodes placed inside.
// A sample is the ball of the rope's radius centred on the curve point C(s) against the body: its
// gap, normal and closest body point are exact for every shape findContacts supports (planes, boxes,
// GJK for convex shapes, triangles of meshes and heightfields, compounds).
//
// For convex bodies the touching set of a piece is one interval (the distance to a convex set is
// convex along a segment, and the curve stays within the capsule's bulge of its chord); for concave
// meshes it is treated as one interval from its first to its last touching parameter.
//
// Not API: installed only because body_contacts.h includes it; may change in any release.

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>

#include <vector>

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/capsule.h"
#include "bullet_bridge/contact.h"
#include "rope/rod/rod.h"

namespace rope::bullet {

struct ContactSample {
  double s = 0.0;       // curve parameter of the sample
  double weight = 0.0;  // m of rest length the sample stands for (Gauss weight x stretch rest length)
  int capsule = -1;     // index of the capsule piece it lies on
  // The ball of the rope's radius at C(s) against the body (distance: the tube's gap, < 0 penetrating;
  // normal: from the body into the rope; pointOnBody: the body's closest point). contact.t is unused.
  Contact contact;
};

class LineContactSampler {
 public:
  // Bisection steps that locate each free end of a touching stretch: the end is found to within
  // (s1 - s0) / 2^(kBisections + 1).
  static constexpr int kBisections = 6;

  // Appends the samples of the capsule piece [s0, s1] (index `capsule`) of `rod` against `object`
  // whose gap is <= reach (m): `points` Gauss-Legendre nodes on the piece's touching stretch.
  // chord: the capsule (radius: the rope's), whose axis ends a and b are C(s0) and C(s1) of the rod's
  // state as CapsuleProxies evaluated them (the same bits as rod.position; not evaluated again).
  // chordContact: the capsule's own contact with the body (findContacts on the chord), which says
  // where the piece is nearest the body. Throws InvalidArgument like findContacts for an unsupported
  // shape (before appending anything).
  void sampleCapsule(const Rod& rod, int capsule, double s0, double s1, const Capsule& chord,
                     const btCollisionObject& object, double reach, const Contact& chordContact, int points,
                     std::vector<ContactSample>& out);

  // The ball of `radius` at `centre` against `object`: the deepest contact within reach (m), if any.
  bool ballContact(const btVector3& centre, btScalar radius, const btCollisionObject& object, double reach,
                   Contact& contact);

 private:
  // C(s) of the rod (Rod::position), the span search started from the last point's span.
  Vec3 positionOf(const Rod& rod, double s);
  bool touching(const Rod& rod, double s, btScalar radius, const btCollisionObject& object, double reach);
  // Boundary of the touching set between a free parameter and a touching one.
  double bisect(const Rod& rod, double free, double inside, btScalar radius, const btCollisionObject& object,
                double reach);

  std::vector<Contact> scratch_;
  Contact probe_;
  int span_ = -1;  // the knot span of the last point positionOf evaluated (a hint: any value is safe)
};

}  // namespace rope::bullet
