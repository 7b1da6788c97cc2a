// SPDX-License-Identifier: MIT
// Bad input, one table (issue 17): every case below calls a public entry point of rope/,
// bullet_bridge/ or render/ with a NaN, infinite, zero, negative, out-of-range or degenerate value and
// must be refused with rope::InvalidArgument naming the parameter (and, where given, its value as
// "parameter = value"), leaving every object of the fixture bit for bit as it was (Fixture::state():
// rods, ropes with their attachments, the kinematic and tractrix ropes, curves, the draw list and
// the Bullet world's object count).
//
// Categories (the table built by allCases() has one row per call; the name of each ctest says which):
//   rope/ settings      RodSettings: every numeric field NaN, infinite, zero or negative, counts and
//                       degree out of range, a stretchingQuadrature or removalCriterion outside the
//                       enum, removalRelativeError outside (0, 1), angles unordered,
//                       a radius whose derived area overflows.
//   rope/ Rod           fromSegment with a == b or NaN ends; fromPolyline with one point or
//                       coincident points; position/strain/pin/addForce/addImpulse/addSpring/
//                       insertKnot/removeKnot/cut with s NaN, outside the rope, at an end, a hair from
//                       a knot or an end, or not a knot; pins coincident or a rounding step apart; NaN targets, forces and
//                       matrices; unknown pin ids; wrong point counts; step with h = 0, < 0, NaN,
//                       inf; the split step without a trial.
//   rope/ spline        knot vectors with degree 0 or decreasing knots; curves with the wrong point
//                       count or an index out of range; interpolation of one point or coincident
//                       points; Gauss rules of 0 points; insertion, removal and split outside.
//   rope/ tractrix      TractrixSettings fields out of range (variant outside the enum, angles,
//                       counts); a one-point or coincident initial shape; a NaN or too distant target.
//   bullet_bridge/      BulletRopeSettings, AttachmentSettings and KinematicRopeSettings fields; a rope
//                       attached with NaN or outside s, NaN local point, in no world, to a foreign
//                       body, to the same body twice at one point; a rope added twice or to a second
//                       world, removed from a world it is not in; cuts at an end or at an attachment;
//                       unknown attachment ids; a substep with h <= 0 or NaN; NaN rays; contact
//                       tests with a negative margin or a shapeless object; a kinematic rope added
//                       twice, following nullptr, a NaN or too distant target, an empty path, a
//                       capsule index out of range.
//   render/             draw-list items with a null mesh, a NaN transform or a colour out of range;
//                       cameras with a NaN eye, parallel up vector, bad field of view or planes;
//                       primitive meshes of zero, negative or NaN size or resolutions out of range;
//                       tubes and polylines with NaN points or bad options; images of 0 pixels;
//                       render settings out of range.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "bullet_bridge/kinematic_rope.h"
#include "bullet_bridge/rope_queries.h"
#include "bullet_bridge/rope_world.h"
#include "reliability/reliability_support.h"
#include "render/camera.h"
#include "render/image.h"
#include "render/polyline_mesh.h"
#include "render/primitive_mesh.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "render/tube_mesh.h"
#include "rope/common/error.h"
#include "rope/spline/bspline_curve.h"
#include "rope/spline/curve_interpolation.h"
#include "rope/spline/curve_split.h"
#include "rope/spline/gauss_legendre.h"
#include "rope/spline/knot_insertion.h"
#include "rope/spline/knot_removal.h"
#include "rope/tractrix/length_angle.h"
#include "rope/tractrix/tractrix_rope.h"

namespace rope {
namespace {

using bullet::AttachmentSettings;
using bullet::BulletRopeSettings;
using bullet::KinematicRope;
using bullet::KinematicRopeSettings;
using bullet::RopeEnd;
using bullet::RopeObject;
using bullet::RopeWorld;
using test::ActionWorld;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Every object the cases act on, built the same way for each case.
struct Fixture {
  ActionWorld bullet{btVector3(0, btScalar(-9.81), 0)};
  btRigidBody* box = bullet.addBox(btVector3(0.05, 0.05, 0.05), 1.0, btVector3(1, 1, 0));
  ActionWorld otherBullet;
  btRigidBody* foreignBody = otherBullet.addBox(btVector3(0.05, 0.05, 0.05), 1.0, btVector3(0, 0, 0));
  RopeWorld ropes{bullet.world()};
  RopeWorld otherRopes{otherBullet.world()};
  RopeObject rope{Rod::fromSegment(RodSettings{}, Vec3(0, 1, 0), Vec3(1, 1, 0))};
  RopeObject loose{Rod::fromSegment(RodSettings{}, Vec3(0, 2, 0), Vec3(1, 2, 0))};  // in no world
  int pinAttachment = 0;
  int boxAttachment = 0;
  Rod rod = Rod::fromSegment(RodSettings{}, Vec3(0, 0, 0), Vec3(1, 0, 0));
  // Winches: a rod with a pin at 0.3 and a clamp at 0.7, a rope with a body attachment at 0.4.
  Rod winchRod = Rod::fromSegment(RodSettings{}, Vec3(0, 0, 0), Vec3(1, 0, 0));
  RopeObject winchRope{Rod::fromSegment(RodSettings{}, Vec3(0, 1, 1), Vec3(1, 1, 1))};
  KinematicRope hose{TractrixRope(PointList{Vec3(0, 3, 0), Vec3(1, 3, 0)}, TractrixSettings{})};
  TractrixRope tractrix{PointList{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0)}, TractrixSettings{}};
  KnotVector knots = KnotVector::clampedUniform(3, 6);
  PointList points{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 1, 0), Vec3(3, 1, 0), Vec3(4, 0, 0), Vec3(5, 0, 0)};
  BSplineCurve curve{knots, points};
  render::Scene scene;

  Fixture() {
    ropes.addRope(rope);
    pinAttachment = rope.attachToPoint(0.0, btVector3(0, 1, 0));
    boxAttachment = rope.attachToBody(1.0, *box, btVector3(0, 0, 0));
    rod.pin(0.0);
    winchRod.pin(0.3);
    winchRod.clamp(0.7);
    ropes.addRope(winchRope);
    winchRope.attachToBody(0.4, *box, btVector3(0, 0, 0));
    hose.addToWorld(bullet.world());
    scene.add(std::make_shared<render::Mesh>(render::makeBox(Vec3(1, 1, 1))));
    bullet.step(2);
  }
  ~Fixture() { hose.removeFromWorld(); }

  std::vector<double> state() const {
    std::vector<double> all = test::rodState(rod);
    const std::vector<double> winchRodState = test::rodState(winchRod);
    all.insert(all.end(), winchRodState.begin(), winchRodState.end());
    for (const RopeObject* r : {&rope, &loose, &winchRope}) {
      for (RopeEnd end : {RopeEnd::kBegin, RopeEnd::kEnd}) {
        const bullet::Winch& w = r->winch(end);
        all.insert(all.end(), {w.speed, w.targetLength, w.stalled ? 1.0 : 0.0, w.paidOut});
      }
      const std::vector<double> part = test::rodState(r->rod());
      all.insert(all.end(), part.begin(), part.end());
      all.push_back(r->world() != nullptr ? 1.0 : 0.0);
      for (const bullet::Attachment& a : r->attachments()) {
        all.insert(all.end(), {static_cast<double>(a.id), a.s, static_cast<double>(a.localPoint.x()),
                               static_cast<double>(a.localPoint.y()), static_cast<double>(a.localPoint.z()),
                               a.body == nullptr ? -1.0 : static_cast<double>(a.body->getWorldArrayIndex()),
                               a.settings.stiffness, a.settings.damping});
      }
    }
    all.push_back(static_cast<double>(ropes.ropes().size()));
    all.push_back(static_cast<double>(otherRopes.ropes().size()));
    for (const TractrixRope* t : {&hose.tractrix(), &tractrix}) {
      for (int i = 0; i < t->knots().size(); ++i) all.push_back(t->knots()[i]);
      for (const Vec3& p : t->controlPoints()) all.insert(all.end(), {p.x(), p.y(), p.z()});
    }
    all.push_back(hose.followedBody() == nullptr ? 0.0 : 1.0);
    all.push_back(hose.world() != nullptr ? 1.0 : 0.0);
    for (int i = 0; i < knots.size(); ++i) all.push_back(knots[i]);
    for (const Vec3& p : points) all.insert(all.end(), {p.x(), p.y(), p.z()});
    for (int i = 0; i < curve.knots().size(); ++i) all.push_back(curve.knots()[i]);
    for (const Vec3& p : curve.controlPoints()) all.insert(all.end(), {p.x(), p.y(), p.z()});
    all.push_back(static_cast<double>(scene.items.size()));
    all.push_back(static_cast<double>(bullet.world().getNumCollisionObjects()));
    all.push_back(static_cast<double>(otherBullet.world().getNumCollisionObjects()));
    return all;
  }
};

struct Case {
  std::string name;       // what is tried (also the ctest name, cleaned)
  std::string parameter;  // InvalidArgument::parameter() expected
  std::string value;      // the value the message must show ("parameter = value"), "" to skip
  std::function<void(Fixture&)> call;
};

// A case on a RodSettings field, through Rod::fromSegment (which validates first).
Case rodSetting(const std::string& name, const std::string& parameter, const std::string& value,
                std::function<void(RodSettings&)> change) {
  return {name, parameter, value, [change](Fixture&) {
            RodSettings settings;
            change(settings);
            Rod::fromSegment(settings, Vec3(0, 0, 0), Vec3(1, 0, 0));
          }};
}

Case ropeSetting(const std::string& name, const std::string& parameter, const std::string& value,
                 std::function<void(BulletRopeSettings&)> change) {
  return {name, parameter, value, [change](Fixture& f) {
            BulletRopeSettings settings;
            change(settings);
            RopeObject rope(f.rod, settings);
          }};
}

Case hoseSetting(const std::string& name, const std::string& parameter, const std::string& value,
                 std::function<void(KinematicRopeSettings&)> change) {
  return {name, parameter, value, [change](Fixture& f) {
            KinematicRopeSettings settings;
            change(settings);
            KinematicRope hose(f.tractrix, settings);
          }};
}

Case tractrixSetting(const std::string& name, const std::string& parameter, const std::string& value,
                     std::function<void(TractrixSettings&)> change) {
  return {name, parameter, value, [change](Fixture&) {
            TractrixSettings settings;
            change(settings);
            TractrixRope rope(PointList{Vec3(0, 0, 0), Vec3(1, 0, 0)}, settings);
          }};
}

Case renderSetting(const std::string& name, const std::string& parameter, const std::string& value,
                   std::function<void(render::RenderSettings&)> change) {
  return {name, parameter, value, [change](Fixture&) {
            render::RenderSettings settings;
            change(settings);
            settings.validate();
          }};
}

Case cameraSetting(const std::string& name, const std::string& parameter, const std::string& value,
                   std::function<void(render::Camera&)> change) {
  return {name, parameter, value, [change](Fixture&) {
            render::Camera camera;
            change(camera);
            camera.validate();
          }};
}

const Eigen::Matrix3d kIdentity = Eigen::Matrix3d::Identity();

std::vector<Case> allCases() {
  std::vector<Case> cases = {
      // ---- rope/: RodSettings ----
      rodSetting("rod restLength 0", "settings.restLength", "0", [](RodSettings& s) { s.restLength = 0; }),
      rodSetting("rod restLength NaN", "settings.restLength", "nan", [](RodSettings& s) { s.restLength = kNaN; }),
      rodSetting("rod radius negative", "settings.radius", "-0.01", [](RodSettings& s) { s.radius = -0.01; }),
      rodSetting("rod radius inf", "settings.radius", "inf", [](RodSettings& s) { s.radius = kInf; }),
      rodSetting("rod radius 1e200 overflows the area", "settings.radius", "9.9999999999999997e+199",
                 [](RodSettings& s) { s.radius = 1e200; }),
      rodSetting("rod linearDensity 0", "settings.linearDensity", "0", [](RodSettings& s) { s.linearDensity = 0; }),
      rodSetting("rod materialDensity NaN", "settings.materialDensity", "nan",
                 [](RodSettings& s) { s.materialDensity = kNaN; }),
      rodSetting("rod youngsModulus 0", "settings.youngsModulus", "0", [](RodSettings& s) { s.youngsModulus = 0; }),
      rodSetting("rod youngsModulus -inf", "settings.youngsModulus", "-inf",
                 [](RodSettings& s) { s.youngsModulus = -kInf; }),
      rodSetting("rod bendingStiffness negative", "settings.bendingStiffness", "-2",
                 [](RodSettings& s) { s.bendingStiffness = -2; }),
      rodSetting("rod massDamping negative", "settings.massDamping", "-1", [](RodSettings& s) { s.massDamping = -1; }),
      rodSetting("rod stiffnessDamping NaN", "settings.stiffnessDamping", "nan",
                 [](RodSettings& s) { s.stiffnessDamping = kNaN; }),
      rodSetting("rod materialDamping negative", "settings.materialDamping", "-0.001",
                 [](RodSettings& s) { s.materialDamping = -1e-3; }),
      rodSetting("rod materialDamping infinite", "settings.materialDamping", "inf",
                 [](RodSettings& s) { s.materialDamping = kInf; }),
      rodSetting("rod gravity NaN", "settings.gravity[1]", "nan", [](RodSettings& s) { s.gravity.y() = kNaN; }),
      rodSetting("rod degree 0", "settings.degree", "0", [](RodSettings& s) { s.degree = 0; }),
      rodSetting("rod degree 99", "settings.degree", "99", [](RodSettings& s) { s.degree = 99; }),
      rodSetting("rod stretchingQuadrature out of enum", "settings.stretchingQuadrature", "7",
                 [](RodSettings& s) { s.stretchingQuadrature = static_cast<StretchingQuadrature>(7); }),
      rodSetting("rod timeIntegrator out of enum", "settings.timeIntegrator", "5",
                 [](RodSettings& s) { s.timeIntegrator = static_cast<TimeIntegrator>(5); }),
      rodSetting("rod minControlPoints below degree+1", "settings.minControlPoints", "3",
                 [](RodSettings& s) { s.minControlPoints = 3; }),
      rodSetting("rod maxControlPoints below min", "settings.maxControlPoints", "3",
                 [](RodSettings& s) {
                   s.minControlPoints = 4;
                   s.maxControlPoints = 3;
                 }),
      rodSetting("rod initialControlPoints above max", "settings.initialControlPoints", "200",
                 [](RodSettings& s) { s.initialControlPoints = 200; }),
      rodSetting("rod insertAngle 0", "settings.insertAngle", "0", [](RodSettings& s) { s.insertAngle = 0; }),
      rodSetting("rod removeAngle below insertAngle", "settings.removeAngle", "1",
                 [](RodSettings& s) { s.removeAngle = 1.0; }),
      rodSetting("rod removalErrorBound 0", "settings.removalErrorBound", "0",
                 [](RodSettings& s) { s.removalErrorBound = 0; }),
      rodSetting("rod removalVelocityErrorBound NaN", "settings.removalVelocityErrorBound", "nan",
                 [](RodSettings& s) { s.removalVelocityErrorBound = kNaN; }),
      rodSetting("rod removalCriterion out of enum", "settings.removalCriterion", "9",
                 [](RodSettings& s) { s.removalCriterion = static_cast<RemovalCriterion>(9); }),
      rodSetting("rod removalRelativeError NaN", "settings.removalRelativeError", "nan",
                 [](RodSettings& s) { s.removalRelativeError = kNaN; }),
      rodSetting("rod removalRelativeError 0", "settings.removalRelativeError", "0",
                 [](RodSettings& s) { s.removalRelativeError = 0.0; }),
      rodSetting("rod removalRelativeError 1", "settings.removalRelativeError", "1",
                 [](RodSettings& s) { s.removalRelativeError = 1.0; }),
      rodSetting("rod removalRelativeError infinite", "settings.removalRelativeError", "inf",
                 [](RodSettings& s) { s.removalRelativeError = kInf; }),
      rodSetting("rod minKnotSpacing negative", "settings.minKnotSpacing", "-0.001",
                 [](RodSettings& s) { s.minKnotSpacing = -0.001; }),

      // ---- rope/: Rod ----
      {"rod fromSegment a == b", "b", "", [](Fixture&) { Rod::fromSegment(RodSettings{}, Vec3(1, 1, 1), Vec3(1, 1, 1)); }},
      {"rod fromSegment a NaN", "a[0]", "nan", [](Fixture&) { Rod::fromSegment(RodSettings{}, Vec3(kNaN, 0, 0), Vec3(1, 0, 0)); }},
      {"rod fromPolyline one point", "points.size()", "1",
       [](Fixture&) { Rod::fromPolyline(RodSettings{}, PointList{Vec3(0, 0, 0)}); }},
      {"rod fromPolyline coincident points", "points[1]", "",
       [](Fixture&) { Rod::fromPolyline(RodSettings{}, PointList{Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)}); }},
      {"rod fromPolyline rest shape out of enum", "rest", "5",
       [](Fixture&) {
         Rod::fromPolyline(RodSettings{}, PointList{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0)},
                           static_cast<Rod::RestShape>(5));
       }},
      {"rod position NaN", "s", "nan", [](Fixture& f) { f.rod.position(kNaN); }},
      {"rod position outside", "s", "1.5", [](Fixture& f) { f.rod.position(1.5); }},
      {"rod strain outside", "s", "-0.5", [](Fixture& f) { f.rod.strain(-0.5); }},
      {"rod pin outside", "s", "2", [](Fixture& f) { f.rod.pin(2.0); }},
      {"rod pin already there", "s", "0", [](Fixture& f) { f.rod.pin(0.0); }},
      {"rod pin a rounding step from another", "s", "", [](Fixture& f) { f.rod.pin(std::nextafter(0.0, 1.0)); }},
      {"rod pin target NaN", "target[2]", "nan", [](Fixture& f) { f.rod.pin(0.5, Vec3(0, 0, kNaN)); }},
      {"rod setPinTarget unknown id", "id", "99", [](Fixture& f) { f.rod.setPinTarget(99, Vec3::Zero()); }},
      {"rod releasePin unknown id", "id", "-3", [](Fixture& f) { f.rod.releasePin(-3); }},
      {"rod addForce NaN", "force[0]", "nan", [](Fixture& f) { f.rod.addForce(0.5, Vec3(kNaN, 0, 0)); }},
      {"rod addForce outside", "s", "", [](Fixture& f) { f.rod.addForce(-1.0, Vec3::Zero()); }},
      {"rod addImpulse inf", "impulse[1]", "inf", [](Fixture& f) { f.rod.addImpulse(0.5, Vec3(0, kInf, 0)); }},
      {"rod addSpring NaN stiffness", "stiffness(1,1)", "nan",
       [](Fixture& f) {
         Eigen::Matrix3d k = kIdentity;
         k(1, 1) = kNaN;
         f.rod.addSpring(0.5, Vec3::Zero(), k, kIdentity);
       }},
      {"rod setControlPoints wrong count", "points.size()", "2",
       [](Fixture& f) { f.rod.setControlPoints(PointList{Vec3::Zero(), Vec3::Zero()}); }},
      {"rod setVelocities NaN", "velocities[3][0]", "nan",
       [](Fixture& f) {
         PointList v = f.rod.velocities();
         v[3].x() = kNaN;
         f.rod.setVelocities(v);
       }},
      {"rod step h 0", "h", "0", [](Fixture& f) { f.rod.step(0.0); }},
      {"rod step h negative", "h", "-0.01", [](Fixture& f) { f.rod.step(-0.01); }},
      {"rod step h NaN", "h", "nan", [](Fixture& f) { f.rod.step(kNaN); }},
      {"rod step h inf", "h", "inf", [](Fixture& f) { f.rod.step(kInf); }},
      {"rod trialVelocities without trial", "trial", "none", [](Fixture& f) { f.rod.trialVelocities(); }},
      {"rod commitTrial without trial", "trial", "none", [](Fixture& f) { f.rod.commitTrial(); }},
      {"rod insertKnot outside", "s", "3", [](Fixture& f) { f.rod.insertKnot(3.0); }},
      {"rod insertKnot a hair from a knot", "s", "", [](Fixture& f) { f.rod.insertKnot(f.rod.knots()[5] + 1e-9); }},
      {"rod cut a hair from the end", "s", "", [](Fixture& f) { f.rod.cut(1.0 - 1e-9); }},
      {"rod removeKnot not a knot", "s", "", [](Fixture& f) { f.rod.removeKnot(0.123456); }},
      {"rod cut at an end", "s", "", [](Fixture& f) { f.rod.cut(1.0); }},
      {"rod cut at a pin", "s", "", [](Fixture& f) { f.rod.cut(0.0); }},

      // ---- rope/: spline ----
      {"knot vector degree 0", "degree", "0", [](Fixture&) { KnotVector(0, {0, 1}); }},
      {"knot vector decreasing", "knots[4]", "", [](Fixture&) { KnotVector(3, {0, 0, 0, 0, -1, 1, 1, 1, 1}); }},
      {"curve wrong point count", "controlPoints.size()", "2",
       [](Fixture& f) { BSplineCurve(f.knots, PointList{Vec3::Zero(), Vec3::Zero()}); }},
      {"curve setControlPoint index out of range", "i", "6", [](Fixture& f) { f.curve.setControlPoint(6, Vec3::Zero()); }},
      {"curve setControlPoint NaN", "point", "", [](Fixture& f) { f.curve.setControlPoint(1, Vec3(kNaN, 0, 0)); }},
      {"curve position outside", "s", "", [](Fixture& f) { f.curve.position(-0.1); }},
      {"interpolate one point", "points.size()", "1", [](Fixture&) { interpolatePolyline(PointList{Vec3::Zero()}); }},
      {"interpolate degree 0", "degree", "0",
       [](Fixture& f) { interpolatePolyline(f.points, 0); }},
      {"interpolate parametrization out of enum", "parametrization", "4",
       [](Fixture& f) { interpolatePolyline(f.points, 3, static_cast<Parametrization>(4)); }},
      {"gauss rule of 0 points", "count", "0", [](Fixture&) { gaussLegendre(0); }},
      {"knot insertion outside", "s", "", [](Fixture& f) { planKnotInsertion(f.knots, 1.5); }},
      {"knot removal not a knot", "s", "", [](Fixture& f) { planKnotRemoval(f.knots, f.points, 0.3); }},
      {"curve split at an end", "s", "", [](Fixture& f) { planCurveSplit(f.knots, 0.0); }},

      // ---- rope/: tractrix ----
      {"length-angle model out of enum", "model", "3",
       [](Fixture&) { pieceLengthShortfall(static_cast<LengthAngleModel>(3), 2.0); }},
      {"length-angle thresholds mergeFraction 1", "mergeFraction", "1", [](Fixture&) { thresholdsForLengthError(0.02, 1.0); }},
      tractrixSetting("tractrix variant out of enum", "settings.variant", "9",
                      [](TractrixSettings& s) { s.variant = static_cast<TractrixVariant>(9); }),
      tractrixSetting("tractrix subdivisionAngle NaN", "settings.subdivisionAngle", "nan",
                      [](TractrixSettings& s) { s.subdivisionAngle = kNaN; }),
      tractrixSetting("tractrix mergingAngle pi", "settings.mergingAngle", "",
                      [](TractrixSettings& s) { s.mergingAngle = kTractrixPi; }),
      tractrixSetting("tractrix lengthGaussPoints 0", "settings.lengthGaussPoints", "0",
                      [](TractrixSettings& s) { s.lengthGaussPoints = 0; }),
      tractrixSetting("tractrix segmentCount 0", "settings.segmentCount", "0",
                      [](TractrixSettings& s) { s.segmentCount = 0; }),
      tractrixSetting("tractrix maxMergeShapeError inf", "settings.maxMergeShapeError", "inf",
                      [](TractrixSettings& s) { s.maxMergeShapeError = kInf; }),
      {"tractrix one-point shape", "initialShape.size()", "1",
       [](Fixture&) { TractrixRope(PointList{Vec3::Zero()}, TractrixSettings{}); }},
      {"tractrix coincident shape", "initialShape[1]", "",
       [](Fixture&) { TractrixRope(PointList{Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(1, 0, 0)}, TractrixSettings{}); }},
      {"tractrix target NaN", "target[1]", "nan", [](Fixture& f) { f.tractrix.moveLeadingEnd(Vec3(0, kNaN, 0)); }},
      {"tractrix target too far", "target[0]", "9.9999999999999997e+199", [](Fixture& f) { f.tractrix.moveLeadingEnd(Vec3(1e200, 0, 0)); }},

      // ---- bullet_bridge/: settings ----
      ropeSetting("rope contactStiffness 0", "settings.contactStiffness", "0",
                  [](BulletRopeSettings& s) { s.contactStiffness = 0; }),
      ropeSetting("rope contactDamping negative", "settings.contactDamping", "-1",
                  [](BulletRopeSettings& s) { s.contactDamping = -1; }),
      ropeSetting("rope speculativeDamping NaN", "settings.speculativeDamping", "nan",
                  [](BulletRopeSettings& s) { s.speculativeDamping = kNaN; }),
      ropeSetting("rope friction negative", "settings.friction", "-0.5",
                  [](BulletRopeSettings& s) { s.friction = -0.5; }),
      ropeSetting("rope frictionVelocity 0", "settings.frictionVelocity", "0",
                  [](BulletRopeSettings& s) { s.frictionVelocity = 0; }),
      ropeSetting("rope fluidDensity negative", "settings.fluidDensity", "-1",
                  [](BulletRopeSettings& s) { s.fluidDensity = -1; }),
      ropeSetting("rope normalDragCoefficient NaN", "settings.normalDragCoefficient", "nan",
                  [](BulletRopeSettings& s) { s.normalDragCoefficient = kNaN; }),
      ropeSetting("rope tangentialDragCoefficient negative", "settings.tangentialDragCoefficient", "-0.01",
                  [](BulletRopeSettings& s) { s.tangentialDragCoefficient = -0.01; }),
      ropeSetting("rope windVelocity inf", "settings.windVelocity.y", "inf",
                  [](BulletRopeSettings& s) { s.windVelocity = btVector3(0, btScalar(kInf), 0); }),
      ropeSetting("rope capsulesPerSpan 0", "settings.capsulesPerSpan", "0",
                  [](BulletRopeSettings& s) { s.capsulesPerSpan = 0; }),
      ropeSetting("rope capsulesPerSpan 17", "settings.capsulesPerSpan", "17",
                  [](BulletRopeSettings& s) { s.capsulesPerSpan = 17; }),
      ropeSetting("rope lineContactStiffness 0", "settings.lineContactStiffness", "0",
                  [](BulletRopeSettings& s) { s.lineContactStiffness = 0; }),
      ropeSetting("rope lineContactDamping NaN", "settings.lineContactDamping", "nan",
                  [](BulletRopeSettings& s) { s.lineContactDamping = kNaN; }),
      ropeSetting("rope lineSpeculativeDamping negative", "settings.lineSpeculativeDamping", "-1",
                  [](BulletRopeSettings& s) { s.lineSpeculativeDamping = -1; }),
      ropeSetting("rope contactQuadraturePoints 0", "settings.contactQuadraturePoints", "0",
                  [](BulletRopeSettings& s) { s.contactQuadraturePoints = 0; }),
      ropeSetting("rope contactQuadraturePoints 9", "settings.contactQuadraturePoints", "9",
                  [](BulletRopeSettings& s) { s.contactQuadraturePoints = 9; }),
      ropeSetting("rope concentratedContactRatio above 1", "settings.concentratedContactRatio", "1.5",
                  [](BulletRopeSettings& s) { s.concentratedContactRatio = 1.5; }),
      ropeSetting("rope gravityScale inf", "settings.gravityScale", "inf",
                  [](BulletRopeSettings& s) { s.gravityScale = kInf; }),
      ropeSetting("rope gravitySource out of range", "settings.gravitySource", "7",
                  [](BulletRopeSettings& s) { s.gravitySource = static_cast<BulletRopeSettings::GravitySource>(7); }),
      ropeSetting("rope speculativeMargin inf", "settings.speculativeMargin", "inf",
                  [](BulletRopeSettings& s) { s.speculativeMargin = kInf; }),
      ropeSetting("rope initialPredictionTime 0", "settings.initialPredictionTime", "0",
                  [](BulletRopeSettings& s) { s.initialPredictionTime = 0; }),
      ropeSetting("rope bodyStabilityFactor above 1", "settings.bodyStabilityFactor", "1.5",
                  [](BulletRopeSettings& s) { s.bodyStabilityFactor = 1.5; }),
      ropeSetting("rope selfContactExclusion negative", "settings.selfContactExclusion", "-2",
                  [](BulletRopeSettings& s) { s.selfContactExclusion = -2; }),
      ropeSetting("rope collisionGroup 0", "settings.collisionGroup", "0",
                  [](BulletRopeSettings& s) { s.collisionGroup = 0; }),
      {"attachment stiffness 0", "attachment.stiffness", "0",
       [](Fixture& f) {
         AttachmentSettings settings;
         settings.stiffness = 0;
         f.rope.attachToBody(0.5, *f.box, btVector3(0, 0, 0), settings);
       }},
      {"attachment damping NaN", "attachment.damping", "nan",
       [](Fixture& f) {
         AttachmentSettings settings;
         settings.damping = kNaN;
         f.rope.attachToBody(0.5, *f.box, btVector3(0, 0, 0), settings);
       }},
      hoseSetting("hose radius 0", "settings.radius", "0", [](KinematicRopeSettings& s) { s.radius = 0; }),
      hoseSetting("hose radius 1e308", "settings.radius", "1e+308", [](KinematicRopeSettings& s) { s.radius = 1e308; }),
      hoseSetting("hose capsulesPerSpan 0", "settings.capsulesPerSpan", "0",
                  [](KinematicRopeSettings& s) { s.capsulesPerSpan = 0; }),
      hoseSetting("hose speculativeMargin 1e300", "settings.speculativeMargin", "1.0000000000000001e+300",
                  [](KinematicRopeSettings& s) { s.speculativeMargin = 1e300; }),
      hoseSetting("hose penetrationRecovery 2", "settings.penetrationRecovery", "2",
                  [](KinematicRopeSettings& s) { s.penetrationRecovery = 2; }),
      hoseSetting("hose friction NaN", "settings.friction", "nan", [](KinematicRopeSettings& s) { s.friction = kNaN; }),
      hoseSetting("hose solverIterations 0", "settings.solverIterations", "0",
                  [](KinematicRopeSettings& s) { s.solverIterations = 0; }),
      hoseSetting("hose collisionGroup 0", "settings.collisionGroup", "0",
                  [](KinematicRopeSettings& s) { s.collisionGroup = 0; }),

      // ---- bullet_bridge/: ropes in a world ----
      {"rope attachToBody s NaN", "s", "nan", [](Fixture& f) { f.rope.attachToBody(kNaN, *f.box, btVector3(0, 0, 0)); }},
      {"rope attachToBody s outside", "s", "1.25",
       [](Fixture& f) { f.rope.attachToBody(1.25, *f.box, btVector3(0, 0, 0)); }},
      {"rope attachToBody localPoint NaN", "localPoint.y", "nan",
       [](Fixture& f) { f.rope.attachToBody(0.5, *f.box, btVector3(0, btScalar(kNaN), 0)); }},
      {"rope attachToBody rope in no world", "rope", "", [](Fixture& f) { f.loose.attachToBody(0.5, *f.box, btVector3(0, 0, 0)); }},
      {"rope attachToBody foreign body", "body", "",
       [](Fixture& f) { f.rope.attachToBody(0.5, *f.foreignBody, btVector3(0, 0, 0)); }},
      {"rope attachToBody same body twice at one point", "s", "1",
       [](Fixture& f) { f.rope.attachToBody(1.0, *f.box, btVector3(0, 0, 0)); }},
      {"rope clampToBody direction zero", "localDirection", "",
       [](Fixture& f) { f.rope.clampToBody(0.5, *f.box, btVector3(0, 0, 0), btVector3(0, 0, 0)); }},
      {"rope clampToBody direction NaN", "localDirection.x", "nan",
       [](Fixture& f) { f.rope.clampToBody(0.5, *f.box, btVector3(0, 0, 0), btVector3(btScalar(kNaN), 0, 1)); }},
      {"rope clampToBody foreign body", "body", "",
       [](Fixture& f) { f.rope.clampToBody(0.5, *f.foreignBody, btVector3(0, 0, 0), btVector3(1, 0, 0)); }},
      {"rope clampToBody angularStiffness 0", "attachment.angularStiffness", "0",
       [](Fixture& f) {
         AttachmentSettings settings;
         settings.angularStiffness = 0.0;
         f.rope.clampToBody(0.5, *f.box, btVector3(0, 0, 0), btVector3(1, 0, 0), settings);
       }},
      // Winches (Rod::payOut, RopeObject::payOut / setWinchSpeed / winchTo; winch.h).
      {"rod payOut NaN", "length", "nan", [](Fixture& f) { f.winchRod.payOut(Rod::End::kBegin, kNaN); }},
      {"rod payOut inf", "length", "inf", [](Fixture& f) { f.winchRod.payOut(Rod::End::kEnd, kInf); }},
      {"rod payOut reels past a pin", "length", "-0.29999999999999999",
       [](Fixture& f) { f.winchRod.payOut(Rod::End::kBegin, -0.3); }},
      {"rod payOut reels past a clamp", "length", "-0.29999999999999999",
       [](Fixture& f) { f.winchRod.payOut(Rod::End::kEnd, -0.3); }},
      {"rod payOut below the minimum length", "length", "-0.999", [](Fixture& f) { f.rod.payOut(Rod::End::kEnd, -0.999); }},
      {"rod payOut end not an End", "end", "7",
       [](Fixture& f) { f.winchRod.payOut(static_cast<Rod::End>(7), 0.1); }},
      {"rope payOut NaN", "length", "nan", [](Fixture& f) { f.winchRope.payOut(RopeEnd::kEnd, kNaN); }},
      {"rope payOut reels past a body attachment", "length", "-0.5",
       [](Fixture& f) { f.winchRope.payOut(RopeEnd::kBegin, -0.5); }},
      {"rope payOut below the minimum length", "length", "-0.999",
       [](Fixture& f) { f.loose.payOut(RopeEnd::kEnd, -0.999); }},
      {"rope payOut end not a RopeEnd", "end", "3", [](Fixture& f) { f.loose.payOut(static_cast<RopeEnd>(3), 0.1); }},
      {"rope setWinchSpeed NaN", "speed", "nan", [](Fixture& f) { f.winchRope.setWinchSpeed(RopeEnd::kBegin, kNaN); }},
      {"rope setWinchSpeed too fast", "speed", "-101",
       [](Fixture& f) { f.winchRope.setWinchSpeed(RopeEnd::kBegin, -101.0); }},
      {"rope setWinchSpeed end not a RopeEnd", "end", "2",
       [](Fixture& f) { f.winchRope.setWinchSpeed(static_cast<RopeEnd>(2), 0.1); }},
      {"rope winchTo restLength NaN", "restLength", "nan",
       [](Fixture& f) { f.winchRope.winchTo(RopeEnd::kEnd, kNaN, 0.1); }},
      {"rope winchTo past a body attachment", "restLength", "0.5",
       [](Fixture& f) { f.winchRope.winchTo(RopeEnd::kBegin, 0.5, 0.1); }},
      {"rope winchTo below the minimum length", "restLength", "0.001",
       [](Fixture& f) { f.loose.winchTo(RopeEnd::kBegin, 0.001, 0.1); }},
      {"rope winchTo speed 0", "speed", "0", [](Fixture& f) { f.winchRope.winchTo(RopeEnd::kEnd, 2.0, 0.0); }},
      {"rope winchTo speed inf", "speed", "inf", [](Fixture& f) { f.winchRope.winchTo(RopeEnd::kEnd, 2.0, kInf); }},
      {"rope winchTension end not a RopeEnd", "end", "9",
       [](Fixture& f) { f.winchRope.winchTension(static_cast<RopeEnd>(9)); }},
      {"rope tension s outside", "s", "2", [](Fixture& f) { f.rope.tension(2.0); }},
      {"rope attachmentTension unknown id", "id", "77", [](Fixture& f) { f.rope.attachmentTension(77); }},
      {"rope attachToPoint point inf", "point.z", "inf",
       [](Fixture& f) { f.rope.attachToPoint(0.5, btVector3(0, 0, btScalar(kInf))); }},
      {"rope attachToPoint where a pin is", "s", "0", [](Fixture& f) { f.rope.attachToPoint(0.0, btVector3(0, 1, 0)); }},
      {"rope setAttachmentTarget unknown id", "id", "77", [](Fixture& f) { f.rope.setAttachmentTarget(77, btVector3(0, 0, 0)); }},
      {"rope setAttachmentTarget of a body attachment", "id", "",
       [](Fixture& f) { f.rope.setAttachmentTarget(f.boxAttachment, btVector3(0, 0, 0)); }},
      {"rope setAttachmentTarget NaN", "point.x", "nan",
       [](Fixture& f) { f.rope.setAttachmentTarget(f.pinAttachment, btVector3(btScalar(kNaN), 0, 0)); }},
      {"rope removeAttachment unknown id", "id", "0", [](Fixture& f) { f.rope.removeAttachment(0); }},
      {"rope cut at an end", "s", "", [](Fixture& f) { f.rope.cut(0.0); }},
      {"rope cut at a body attachment", "s", "1", [](Fixture& f) { f.rope.cut(1.0); }},
      {"rope cut NaN", "s", "nan", [](Fixture& f) { f.rope.cut(kNaN); }},
      {"rope cut a hair from the start", "s", "9.9999999999999995e-08", [](Fixture& f) { f.rope.cut(1e-7); }},
      {"rope added twice", "rope", "", [](Fixture& f) { f.ropes.addRope(f.rope); }},
      {"rope in two worlds", "rope", "", [](Fixture& f) { f.otherRopes.addRope(f.rope); }},
      {"rope removed from a world it is not in", "rope", "", [](Fixture& f) { f.otherRopes.removeRope(f.rope); }},
      {"rope substep h 0", "h", "0", [](Fixture& f) { f.loose.substep({}, 0.0); }},
      {"rope substep h NaN", "h", "nan", [](Fixture& f) { f.loose.substep({}, kNaN); }},
      {"rope applyDistributedForce s0 NaN", "s0", "nan",
       [](Fixture& f) { f.rope.applyDistributedForce(kNaN, 1.0, btVector3(1, 0, 0)); }},
      {"rope applyDistributedForce s1 outside", "s1", "1.5",
       [](Fixture& f) { f.rope.applyDistributedForce(0.0, 1.5, btVector3(1, 0, 0)); }},
      {"rope applyDistributedForce empty stretch", "s1", "0.5",
       [](Fixture& f) { f.rope.applyDistributedForce(0.5, 0.5, btVector3(1, 0, 0)); }},
      {"rope applyDistributedForce force inf", "forcePerLength[2]", "inf",
       [](Fixture& f) { f.rope.applyDistributedForce(0.0, 1.0, btVector3(0, 0, btScalar(kInf))); }},
      {"ray from NaN", "from.x", "nan",
       [](Fixture& f) { bullet::rayTestRopes(f.ropes, btVector3(btScalar(kNaN), 0, 0), btVector3(1, 1, 1)); }},
      {"contact test margin negative", "margin", "-0.1",
       [](Fixture& f) { bullet::contactTest(f.ropes, *f.box, -0.1); }},
      {"contact test shapeless object", "object.shape", "null",
       [](Fixture& f) {
         btCollisionObject shapeless;
         bullet::contactTest(f.ropes, shapeless, 0.0);
       }},
      {"hose added to a world twice", "world", "", [](Fixture& f) { f.hose.addToWorld(f.otherBullet.world()); }},
      {"hose follows nullptr", "body", "nullptr", [](Fixture& f) { f.hose.followBodyPoint(nullptr, btVector3(0, 0, 0)); }},
      {"hose follows NaN local point", "localPoint.z", "nan",
       [](Fixture& f) { f.hose.followBodyPoint(f.box, btVector3(0, 0, btScalar(kNaN))); }},
      {"hose target NaN", "target.x", "nan", [](Fixture& f) { f.hose.setTarget(btVector3(btScalar(kNaN), 0, 0)); }},
      {"hose target too far", "target.y", "", [](Fixture& f) { f.hose.setTarget(btVector3(0, btScalar(1e200), 0)); }},
      {"hose empty path", "path", "", [](Fixture& f) { f.hose.followPath(nullptr); }},
      {"hose capsule index out of range", "i", "-1", [](Fixture& f) { f.hose.capsule(-1); }},

      // ---- render/ ----
      {"scene add null mesh", "mesh", "", [](Fixture& f) { f.scene.add(nullptr); }},
      {"scene add NaN transform", "transform", "",
       [](Fixture& f) {
         Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
         t.translation().x() = kNaN;
         f.scene.add(std::make_shared<render::Mesh>(render::makeBox(Vec3(1, 1, 1))), t);
       }},
      {"scene add colour above 1", "colour[0]", "2",
       [](Fixture& f) {
         f.scene.add(std::make_shared<render::Mesh>(render::makeBox(Vec3(1, 1, 1))), Eigen::Isometry3d::Identity(),
                     render::Rgb(2.0f, 0.0f, 0.0f));
       }},
      cameraSetting("camera eye NaN", "camera.eye", "", [](render::Camera& c) { c.eye.x() = kNaN; }),
      cameraSetting("camera up parallel to the view", "camera.up", "", [](render::Camera& c) { c.up = c.eye - c.target; }),
      cameraSetting("camera field of view 180", "camera.verticalFovDegrees", "180",
                    [](render::Camera& c) { c.verticalFovDegrees = 180; }),
      cameraSetting("camera far plane before near", "camera.farPlane", "0.01", [](render::Camera& c) { c.farPlane = 0.01; }),
      {"box mesh zero size", "halfExtents.y", "0", [](Fixture&) { render::makeBox(Vec3(1, 0, 1)); }},
      {"box mesh negative size", "halfExtents.x", "-1", [](Fixture&) { render::makeBox(Vec3(-1, 1, 1)); }},
      {"sphere mesh NaN radius", "radius", "nan", [](Fixture&) { render::makeSphere(kNaN, 16); }},
      {"sphere mesh 2 segments", "segments", "2", [](Fixture&) { render::makeSphere(1.0, 2); }},
      {"tube mesh NaN point", "points[2]", "",
       [](Fixture& f) {
         PointList points = f.points;
         points[2].y() = kNaN;
         render::buildTubeMesh(f.knots, points);
       }},
      {"tube mesh radius 0", "options.radius", "0",
       [](Fixture& f) {
         render::TubeOptions options;
         options.radius = 0;
         render::buildTubeMesh(f.knots, f.points, options);
       }},
      {"polyline mesh sides 2", "options.sides", "2",
       [](Fixture& f) {
         render::PolylineOptions options;
         options.sides = 2;
         render::buildPolylineMesh(f.points, options);
       }},
      {"image of 0 pixels", "width", "0", [](Fixture&) { render::Image(0, 10); }},
      renderSetting("render width 0", "settings.width", "0", [](render::RenderSettings& s) { s.width = 0; }),
      renderSetting("render samples 3", "settings.samples", "3", [](render::RenderSettings& s) { s.samples = 3; }),
      renderSetting("render shadowMapSize 100", "settings.shadowMapSize", "100",
                    [](render::RenderSettings& s) { s.shadowMapSize = 100; }),
      renderSetting("render gridSpacing NaN", "settings.gridSpacing", "nan",
                    [](render::RenderSettings& s) { s.gridSpacing = kNaN; }),
  };
  return cases;
}

const std::vector<Case>& cases() {
  static const std::vector<Case> table = allCases();
  return table;
}

class BadInput : public ::testing::TestWithParam<std::size_t> {};

TEST_P(BadInput, IsRefusedNamingTheParameterAndChangesNothing) {
  const Case& c = cases()[GetParam()];
  SCOPED_TRACE(c.name);
  Fixture fixture;
  const std::vector<double> before = fixture.state();
  try {
    c.call(fixture);
    ADD_FAILURE() << "accepted: " << c.name;
  } catch (const InvalidArgument& error) {
    EXPECT_EQ(error.parameter(), c.parameter) << error.what();
    if (!c.value.empty()) {
      EXPECT_NE(std::string(error.what()).find(c.parameter + " = " + c.value), std::string::npos) << error.what();
    }
  } catch (const std::exception& error) {
    ADD_FAILURE() << "not an InvalidArgument: " << error.what();
  }
  EXPECT_TRUE(test::sameBits(fixture.state(), before)) << "the fixture changed";
}

TEST(BadInputTable, HasAtLeastSixtyCasesWithUniqueNames) {
  EXPECT_GE(cases().size(), 60u);
  std::vector<std::string> names;
  for (const Case& c : cases()) names.push_back(c.name);
  std::sort(names.begin(), names.end());
  EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end());
}

std::string caseName(const ::testing::TestParamInfo<std::size_t>& info) {
  std::string name;
  for (const char c : cases()[info.param].name) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Table, BadInput, ::testing::Range<std::size_t>(0, cases().size()), caseName);

}  // namespace
}  // namespace rope
