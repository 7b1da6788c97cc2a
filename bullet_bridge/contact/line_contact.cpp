// SPDX-License-Identifier: MIT
#include "bullet_bridge/contact/line_contact.h"

#include "bullet_bridge/detail/bullet_math.h"
#include "bullet_bridge/find_contacts.h"
#include "rope/spline/bspline_curve.h"
#include "rope/spline/gauss_legendre.h"

namespace rope::bullet {

bool LineContactSampler::ballContact(const btVector3& centre, btScalar radius, const btCollisionObject& object,
                                     double reach, Contact& contact) {
  Capsule ball;
  ball.a = centre;
  ball.b = centre;
  ball.radius = radius;
  scratch_.clear();
  findContacts(ball, object, reach, scratch_);
  if (scratch_.empty()) return false;
  std::size_t deepest = 0;
  for (std::size_t i = 1; i < scratch_.size(); ++i)
    if (scratch_[i].distance < scratch_[deepest].distance) deepest = i;
  contact = scratch_[deepest];
  return true;
}

Vec3 LineContactSampler::positionOf(const Rod& rod, double s) {
  // rod.position(s), bitwise; the span search starts from the last one's (one capsule piece lies in
  // one knot span, so it mostly finds it at once).
  return curvePositionNear(rod.knots(), rod.controlPoints(), s, span_);
}

bool LineContactSampler::touching(const Rod& rod, double s, btScalar radius, const btCollisionObject& object,
                                  double reach) {
  return ballContact(toBullet(positionOf(rod, s)), radius, object, reach, probe_);
}

double LineContactSampler::bisect(const Rod& rod, double free, double inside, btScalar radius,
                                  const btCollisionObject& object, double reach) {
  for (int i = 0; i < kBisections; ++i) {
    const double middle = 0.5 * (free + inside);
    (touching(rod, middle, radius, object, reach) ? inside : free) = middle;
  }
  return inside;
}

void LineContactSampler::sampleCapsule(const Rod& rod, int capsule, double s0, double s1, const Capsule& chord,
                                       const btCollisionObject& object, double reach, const Contact& chordContact,
                                       int points, std::vector<ContactSample>& out) {
  const btScalar radius = chord.radius;
  const double nearest = s0 + static_cast<double>(chordContact.t) * (s1 - s0);
  const bool atStart = ballContact(chord.a, radius, object, reach, probe_);  // touching(rod, s0, ...)
  const bool atEnd = ballContact(chord.b, radius, object, reach, probe_);
  const bool atNearest = touching(rod, nearest, radius, object, reach);
  if (!atStart && !atEnd && !atNearest) return;  // the chord touched, the curve does not
  // The touching stretch [a, b]: from the first to the last touching parameter, ends bisected.
  double a = atStart ? s0 : (atNearest ? nearest : s1);
  double b = atEnd ? s1 : (atNearest ? nearest : s0);
  if (!atStart) a = bisect(rod, s0, a, radius, object, reach);
  if (!atEnd) b = bisect(rod, s1, b, radius, object, reach);
  if (!(b > a)) return;  // a touching point of zero length carries no pressure
  const GaussRule rule = gaussLegendre(points);
  for (int q = 0; q < rule.count; ++q) {
    ContactSample sample;
    sample.s = 0.5 * (a + b) + 0.5 * (b - a) * rule.nodes[q];
    if (!ballContact(toBullet(positionOf(rod, sample.s)), radius, object, reach, sample.contact)) continue;
    // integral over [a, b] of f dl0 = (b - a)/2 sum_q w_q f(s_q) l0'(s_q)
    // l0'(s) = rod.restMetric(s), bitwise, from the span positionOf just found.
    const double restMetric = evaluateCurveNear(rod.knots(), rod.restControlPoints(), sample.s, span_).firstDerivative.norm();
    sample.weight = 0.5 * (b - a) * rule.weights[q] * restMetric;
    sample.capsule = capsule;
    out.push_back(sample);
  }
}

}  // namespace rope::bullet
