// SPDX-License-Identifier: MIT
#include "bullet_bridge/narrowphase/convex_contact.h"

#include <ccd/ccd.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "bullet_bridge/narrowphase/segment_convex_distance.h"
#include "rope/common/error.h"

namespace rope::bullet {

namespace {

// libccd objects, both in the core's local frame.
struct CcdBody {
  const ConvexCore* core;
};
struct CcdCapsule {
  btVector3 p, q;
  btScalar radius;   // capsule radius inflated by the speculative margin
  btVector3 centre;  // the interior point MPR starts its ray from
};

btVector3 toBt(const ccd_vec3_t* v) { return btVector3(v->v[0], v->v[1], v->v[2]); }
void toCcd(const btVector3& b, ccd_vec3_t* v) {
  v->v[0] = b.x();
  v->v[1] = b.y();
  v->v[2] = b.z();
}

// Unit vector along d, or zero for a zero direction (the rounding then adds nothing).
btVector3 unitOrZero(const btVector3& d) {
  const btScalar length = d.length();
  return length > 0 ? d / length : btVector3(0, 0, 0);
}

void bodySupport(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out) {
  const ConvexCore& core = *static_cast<const CcdBody*>(object)->core;
  const btVector3 d = toBt(direction);
  toCcd(core.support(d) + unitOrZero(d) * core.rounding, out);
}

void bodyCenter(const void* object, ccd_vec3_t* out) {
  toCcd(static_cast<const CcdBody*>(object)->core->interiorPoint, out);
}

void capsuleSupport(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out) {
  const CcdCapsule& capsule = *static_cast<const CcdCapsule*>(object);
  const btVector3 d = toBt(direction);
  const btVector3& end = (capsule.q - capsule.p).dot(d) > 0 ? capsule.q : capsule.p;
  toCcd(end + unitOrZero(d) * capsule.radius, out);
}

void capsuleCenter(const void* object, ccd_vec3_t* out) {
  toCcd(static_cast<const CcdCapsule*>(object)->centre, out);
}

btScalar closestAxisParameter(const btVector3& x, const btVector3& p, const btVector3& q) {
  const btVector3 axis = q - p;
  const btScalar length2 = axis.length2();
  if (!(length2 > 0)) return 0;
  return std::min(btScalar(1), std::max(btScalar(0), (x - p).dot(axis) / length2));
}

// The axis enters the core: MPR on the capsule inflated by the margin. MPR finding no overlap would
// contradict GJK (the inflated shapes overlap by at least radius + rounding + margin > 0), so it
// throws NumericalFailure rather than dropping a deep contact silently.
void deepContact(const btVector3& p, const btVector3& q, btScalar radius, const ConvexCore& core,
                 btScalar margin, Contact& local) {
  CcdBody body{&core};
  // MPR measures the depth along the ray between the two interior points. Starting the capsule's
  // ray at the axis point nearest the body's interior point makes that ray perpendicular to the
  // rope (a rope is pushed out sideways, never along itself), and it is then the minimum
  // translation for a body centred on the rope's line. If the body's point lies on the axis, the
  // ray would be degenerate (libccd would nudge it along x): offset it sideways by half the radius,
  // which keeps it inside the capsule.
  const btVector3 interior = core.interiorPoint;
  const btScalar t = closestAxisParameter(interior, p, q);
  btVector3 centre = p + (q - p) * t;
  const btScalar scale = std::max({btScalar(1), core.size, (q - p).length()});
  if ((centre - interior).length2() <= (1e-9 * scale) * (1e-9 * scale)) {
    const btVector3 axis = q - p;
    btVector3 side, unused;
    btPlaneSpace1(axis.length2() > 0 ? axis.normalized() : btVector3(1, 0, 0), side, unused);
    centre += side * (radius / 2);
  }
  CcdCapsule inflated{p, q, radius + margin, centre};
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = bodySupport;
  ccd.center1 = bodyCenter;
  ccd.support2 = capsuleSupport;
  ccd.center2 = capsuleCenter;
  ccd.max_iterations = 200;
  ccd.mpr_tolerance = 1e-12 * scale;
  ccd_real_t depth = 0;
  ccd_vec3_t direction, position;
  const int rc = ccdMPRPenetration(&body, &inflated, &ccd, &depth, &direction, &position);
  const btVector3 normal = toBt(&direction);
  if (rc != 0 || !std::isfinite(depth) || !(depth > 0) || !std::isfinite(normal.length2()) ||
      !(std::fabs(normal.length2() - 1) < 1e-6)) {
    throw NumericalFailure("capsule-convex contact: libccd MPR found no penetration although the "
                           "capsule axis meets the shape (depth " + formatValue(depth) + ")");
  }
  // libccd: moving the capsule (object 2) by depth * direction separates, so `direction` points
  // from the body into the rope. Its `position` is a barycentric mix that includes the interior
  // points, not a surface point, so it is not used: the contact acts at the ray's axis point and
  // the surface points follow from the normal and the distance.
  local.normal = normal;
  local.distance = margin - depth;
  local.t = t;
  local.pointOnCapsule = p + (q - p) * local.t - normal * radius;
  local.pointOnBody = local.pointOnCapsule - normal * local.distance;
}

}  // namespace

bool convexContact(const Capsule& capsule, const ConvexCore& core, const btTransform& coreToWorld,
                   btScalar margin, Contact& contact) {
  const btTransform worldToCore = coreToWorld.inverse();
  const btVector3 p = worldToCore * capsule.a;
  const btVector3 q = worldToCore * capsule.b;
  const btScalar reach = capsule.radius + core.rounding;

  const SegmentConvexDistance closest = segmentConvexDistance(p, q, core, reach + margin);
  Contact local;
  switch (closest.status) {
    case SegmentConvexDistance::Status::BeyondCutoff:
      return false;
    case SegmentConvexDistance::Status::Separated: {
      local.distance = closest.distance - reach;
      if (local.distance > margin) return false;
      local.normal = (closest.pointOnSegment - closest.pointOnCore) / closest.distance;
      local.t = closest.t;
      local.pointOnBody = closest.pointOnCore + local.normal * core.rounding;
      local.pointOnCapsule = closest.pointOnSegment - local.normal * capsule.radius;
      break;
    }
    case SegmentConvexDistance::Status::Intersecting:
      deepContact(p, q, capsule.radius, core, margin, local);
      break;
  }
  contact = local;
  contact.normal = coreToWorld.getBasis() * local.normal;
  contact.pointOnBody = coreToWorld * local.pointOnBody;
  contact.pointOnCapsule = coreToWorld * local.pointOnCapsule;
  return true;
}

}  // namespace rope::bullet
