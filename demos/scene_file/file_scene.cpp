// SPDX-License-Identifier: MIT
#include "demos/scene_file/file_scene.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "demos/scene_file/scene_file_error.h"
#include "demos/scenes/pile_scene.h"
#include "demos/scenes/scene_state.h"
#include "rope/common/error.h"

namespace rope::demos {

namespace {

constexpr double kPi = 3.14159265358979323846;

btQuaternion toBulletRotation(const Eigen::Vector4d& q) {
  return btQuaternion(static_cast<btScalar>(q[0]), static_cast<btScalar>(q[1]), static_cast<btScalar>(q[2]),
                      static_cast<btScalar>(q[3]));
}

// Runs a library call for the file item at `path`: its InvalidArgument (naming "s", "point", ...)
// becomes a SceneFileError at path.<parameter>.
void atPath(const std::string& path, const std::function<void()>& call) {
  try {
    call();
  } catch (const SceneFileError&) {
    throw;
  } catch (const InvalidArgument& error) {
    const LibraryErrorParts parts = splitLibraryError(error);
    throw SceneFileError(path + "." + error.parameter(), parts.value, parts.reason);
  }
}

PointList helixPoints(const RopeShapeDescription& shape) {
  const int count = std::max(2, static_cast<int>(std::ceil(shape.turns * shape.pointsPerTurn)) + 1);
  PointList points;
  for (int i = 0; i < count; ++i) {
    const double u = shape.turns * i / (count - 1);  // turns so far
    const double angle = 2.0 * kPi * u;
    points.push_back(shape.center + Vec3(shape.radius * std::cos(angle), shape.pitch * u, shape.radius * std::sin(angle)));
  }
  return points;
}

// The pile scene's coil (pileCoilPolyline), its lowest point's underside at center.y, moved to
// (center.x, center.z). Its InvalidArgument names the pile's fields; they are renamed to the file's.
PointList coilPoints(const RopeDescription& rope, const std::string& path) {
  PileSceneSettings pile;
  pile.ropeLength = rope.rod.restLength;
  pile.dropHeight = rope.shape.center.y();
  pile.coilRadius = rope.shape.radius;
  pile.coilPitch = rope.shape.pitch;
  pile.tilt = rope.shape.tilt;
  pile.rod = rope.rod;
  pile.bridge = rope.bridge;
  PointList points;
  try {
    points = pileCoilPolyline(pile);
  } catch (const InvalidArgument& error) {
    const std::string names[][2] = {{"settings.ropeLength", "settings.restLength"},
                                    {"settings.dropHeight", "shape.center[1]"},
                                    {"settings.coilRadius", "shape.radius"},
                                    {"settings.coilPitch", "shape.pitch"},
                                    {"settings.tilt", "shape.tilt"}};
    std::string parameter = error.parameter();
    for (const auto& name : names) {
      if (parameter == name[0]) parameter = name[1];
    }
    const LibraryErrorParts parts = splitLibraryError(error);
    throw SceneFileError(path + "." + parameter, parts.value, parts.reason);
  }
  // Moved only where asked, so that a coil at x = z = 0 is bitwise the pile scene's.
  for (Vec3& p : points) {
    if (rope.shape.center.x() != 0.0) p.x() += rope.shape.center.x();
    if (rope.shape.center.z() != 0.0) p.z() += rope.shape.center.z();
  }
  return points;
}

// The Bullet shape of a body that is not a triangle mesh or a .bullet file (those: nullptr).
std::unique_ptr<btCollisionShape> convexOrPlaneShape(const BodyDescription& body) {
  std::unique_ptr<btCollisionShape> shape;
  switch (body.shape) {
    case BodyDescription::Shape::kBox: shape = std::make_unique<btBoxShape>(toBullet(body.halfExtents)); break;
    case BodyDescription::Shape::kSphere: shape = std::make_unique<btSphereShape>(static_cast<btScalar>(body.radius)); break;
    case BodyDescription::Shape::kCapsule: {
      const btScalar radius = static_cast<btScalar>(body.radius), height = static_cast<btScalar>(body.height);
      if (body.axis == 0) shape = std::make_unique<btCapsuleShapeX>(radius, height);
      if (body.axis == 1) shape = std::make_unique<btCapsuleShape>(radius, height);
      if (body.axis == 2) shape = std::make_unique<btCapsuleShapeZ>(radius, height);
      break;
    }
    case BodyDescription::Shape::kCylinder:
      if (body.axis == 0) shape = std::make_unique<btCylinderShapeX>(toBullet(body.halfExtents));
      if (body.axis == 1) shape = std::make_unique<btCylinderShape>(toBullet(body.halfExtents));
      if (body.axis == 2) shape = std::make_unique<btCylinderShapeZ>(toBullet(body.halfExtents));
      break;
    case BodyDescription::Shape::kPlane:
      shape = std::make_unique<btStaticPlaneShape>(toBullet(body.normal), static_cast<btScalar>(body.offset));
      break;
    case BodyDescription::Shape::kMesh:
      if (body.meshType == BodyDescription::MeshType::kConvexHull) {
        auto hull = std::make_unique<btConvexHullShape>();
        for (const Vec3& vertex : body.meshVertices) hull->addPoint(toBullet(vertex), false);
        hull->setMargin(static_cast<btScalar>(body.margin));
        hull->recalcLocalAabb();
        shape = std::move(hull);
      }
      break;
    case BodyDescription::Shape::kBulletFile:
      break;  // imported above
  }
  return shape;
}

// A distributed force's [s0, s1] on the rope as built, checked before simulating (as
// RopeObject::applyDistributedForce checks it when the force is applied).
void checkForceStretch(const bullet::RopeObject& rope, const EventDescription& event) {
  const double s0 = FileScene::parameter(rope, event.s0);
  const double s1 = FileScene::parameter(rope, event.s1);
  if (s0 < rope.rod().beginParameter() || s0 > rope.rod().endParameter()) {
    throw SceneFileError(event.path + ".s0", formatValue(s0),
                         "must be on the rope, in [" + formatValue(rope.rod().beginParameter()) + ", " +
                             formatValue(rope.rod().endParameter()) + "]");
  }
  if (s1 > rope.rod().endParameter()) {
    throw SceneFileError(event.path + ".s1", formatValue(s1),
                         "must be on the rope, <= its end " + formatValue(rope.rod().endParameter()));
  }
  if (!(s1 > s0)) throw SceneFileError(event.path + ".s1", formatValue(s1), "must be > s0 = " + formatValue(s0));
}

}  // namespace

btVector3 FileScene::OwnGravity::at(double t) const {
  const double ramp = rampTime > 0.0 ? std::min(1.0, t / rampTime) : 1.0;
  return gravity * static_cast<btScalar>(ramp);
}

btTransform keyframePose(const std::vector<Keyframe>& keyframes, double t) {
  btTransform pose;
  pose.setIdentity();
  if (keyframes.empty()) return pose;
  std::size_t next = 0;
  while (next < keyframes.size() && keyframes[next].time < t) ++next;
  if (next == 0 || next == keyframes.size()) {
    const Keyframe& held = keyframes[next == 0 ? 0 : keyframes.size() - 1];
    pose.setOrigin(toBullet(held.position));
    pose.setRotation(toBulletRotation(held.rotation));
    return pose;
  }
  const Keyframe& a = keyframes[next - 1];
  const Keyframe& b = keyframes[next];
  double u = (t - a.time) / (b.time - a.time);
  if (a.interpolation == Keyframe::Interpolation::kSmoothstep) u = u * u * (3.0 - 2.0 * u);  // smoothstep
  pose.setOrigin(toBullet(Vec3(a.position + u * (b.position - a.position))));
  pose.setRotation(toBulletRotation(a.rotation).slerp(toBulletRotation(b.rotation), static_cast<btScalar>(u)));
  return pose;
}

double FileScene::parameter(const bullet::RopeObject& rope, const RopeParameter& s) {
  switch (s.kind) {
    case RopeParameter::Kind::kBegin: return rope.rod().beginParameter();
    case RopeParameter::Kind::kEnd: return rope.rod().endParameter();
    case RopeParameter::Kind::kValue: break;
  }
  return s.value;
}

FileScene::FileScene(SceneDescription description, bool checksEnabled)
    : description_(std::move(description)),
      physics_(toBullet(description_.gravity)),
      checks_(description_.checks),
      checksEnabled_(checksEnabled) {
  for (const BodyDescription& body : description_.bodies) buildBody(body);
  for (std::size_t i = 0; i < description_.ropes.size(); ++i) buildRope(description_.ropes[i], i);
  eventDone_.assign(description_.events.size(), false);
  // What needs the built ropes: parameters of events and checks on ropes that exist from the start.
  for (const EventDescription& event : description_.events) {
    const bullet::RopeObject* rope = findRope(event.rope);
    if (rope == nullptr) continue;
    if (event.kind == EventDescription::Kind::kCut || event.kind == EventDescription::Kind::kRopeForce) {
      atPath(event.path, [&] { (void)rope->rod().position(parameter(*rope, event.s)); });
    }
    if (event.kind == EventDescription::Kind::kRopeDistributedForce) checkForceStretch(*rope, event);
    if (event.kind == EventDescription::Kind::kRelease && !attachmentId(event.rope, event.attachment)) {
      throw SceneFileError(event.path + ".attachment", "\"" + event.attachment + "\"", "the rope has no pin or attachment of that name");
    }
  }
  for (const CheckDescription& check : description_.checks) {
    const bullet::RopeObject* rope = findRope(check.rope);
    if (rope == nullptr) continue;
    if (check.s) atPath(check.path, [&] { (void)rope->rod().position(parameter(*rope, *check.s)); });
    if (!check.attachment.empty() && !attachmentId(check.rope, check.attachment)) {
      throw SceneFileError(check.path + ".attachment", "\"" + check.attachment + "\"", "the rope has no pin or attachment of that name");
    }
  }
}

FileScene::~FileScene() {
  for (RopeEntry& rope : ropes_) {
    if (rope.rope->world() != nullptr) physics_.ropes().removeRope(*rope.rope);
  }
}

void FileScene::buildBody(const BodyDescription& body) {
  if (body.shape == BodyDescription::Shape::kBulletFile) {
    imports_.push_back(std::make_unique<BulletFileImport>(physics_.world(), body.file));
    for (const auto& [name, rigidBody] : imports_.back()->bodies()) bodies_[body.name + "/" + name] = rigidBody;
    return;
  }
  std::unique_ptr<btCollisionShape> shape = convexOrPlaneShape(body);
  btTransform transform;
  transform.setIdentity();
  if (body.motion == BodyDescription::Motion::kKinematic && !body.keyframes.empty()) {
    transform = keyframePose(body.keyframes, 0.0);
  } else if (body.shape != BodyDescription::Shape::kPlane) {
    transform.setOrigin(toBullet(body.position));
    transform.setRotation(toBulletRotation(body.rotation));
  }
  const double mass = body.motion == BodyDescription::Motion::kDynamic ? body.mass : 0.0;
  btRigidBody* added = nullptr;
  if (shape) {
    added = physics_.addBody(std::move(shape), mass, transform);
  } else {  // a static triangle mesh (the reader allows no other)
    auto mesh = std::make_unique<btTriangleMesh>();
    for (const std::array<int, 3>& triangle : body.meshTriangles) {
      mesh->addTriangle(toBullet(body.meshVertices[triangle[0]]), toBullet(body.meshVertices[triangle[1]]),
                        toBullet(body.meshVertices[triangle[2]]));
    }
    added = physics_.addStaticMesh(std::move(mesh), transform);
  }
  if (body.friction != 0.5) added->setFriction(static_cast<btScalar>(body.friction));
  added->setRestitution(static_cast<btScalar>(body.restitution));
  if (body.motion == BodyDescription::Motion::kKinematic) {
    added->setCollisionFlags((added->getCollisionFlags() & ~btCollisionObject::CF_STATIC_OBJECT) |
                             btCollisionObject::CF_KINEMATIC_OBJECT);
    added->setActivationState(DISABLE_DEACTIVATION);
    if (!body.keyframes.empty()) kinematicBodies_.emplace_back(added, body.keyframes);
  } else if (body.motion == BodyDescription::Motion::kDynamic) {
    // Awake throughout by default: a body the rope holds or pulls must not be put to sleep by Bullet
    // while the rope's impulses are small (they do not wake it).
    if (!body.canSleep) added->setActivationState(DISABLE_DEACTIVATION);
    added->setLinearVelocity(toBullet(body.linearVelocity));
    added->setAngularVelocity(toBullet(body.angularVelocity));
    if (body.gravity) {
      // Its own gravity (e.g. a load hanging over an ideal pulley), set every step (applyScript).
      added->setFlags(added->getFlags() | BT_DISABLE_WORLD_GRAVITY);
      ownGravity_.push_back({added, toBullet(*body.gravity), body.gravityRampTime});
      added->setGravity(ownGravity_.back().at(0.0));
    }
  }
  bodies_[body.name] = added;
}

void FileScene::buildRope(const RopeDescription& rope, std::size_t index) {
  const std::string path = "ropes[" + std::to_string(index) + "]";
  RopeEntry entry;
  entry.name = rope.name;
  entry.showControlPolygon = rope.showControlPolygon;
  atPath(path + ".shape", [&] {
    const RopeShapeDescription& shape = rope.shape;
    switch (shape.kind) {
      case RopeShapeDescription::Kind::kSegment:
        entry.rope = std::make_unique<bullet::RopeObject>(Rod::fromSegment(rope.rod, shape.from, shape.to), rope.bridge);
        break;
      case RopeShapeDescription::Kind::kPolyline:
        entry.rope = std::make_unique<bullet::RopeObject>(Rod::fromPolyline(rope.rod, shape.points, shape.restShape), rope.bridge);
        break;
      case RopeShapeDescription::Kind::kHelix:
        entry.rope = std::make_unique<bullet::RopeObject>(Rod::fromPolyline(rope.rod, helixPoints(shape), shape.restShape), rope.bridge);
        break;
      case RopeShapeDescription::Kind::kCoil:
        entry.rope = std::make_unique<bullet::RopeObject>(
            Rod::fromPolyline(rope.rod, coilPoints(rope, path), Rod::RestShape::kAsGiven), rope.bridge);
        break;
    }
  });
  bullet::RopeObject& object = *entry.rope;
  physics_.ropes().addRope(object);
  for (const PinDescription& pin : rope.pins) {
    atPath(pin.path, [&] {
      const double s = parameter(object, pin.s);
      (void)object.rod().position(s);
      Vec3 target = pin.target.value_or(object.rod().position(s));
      if (!pin.keyframes.empty()) target = pin.keyframes.front().position;
      const int id = object.attachToPoint(s, toBullet(target));
      if (!pin.name.empty()) entry.ids[pin.name] = id;
      if (!pin.keyframes.empty()) movingPins_.push_back({rope.name, id, pin.keyframes});
    });
  }
  for (const AttachmentDescription& attachment : rope.attachments) {
    btRigidBody& body = *bodies_.at(attachment.body);
    atPath(attachment.path, [&] {
      const double s = parameter(object, attachment.s);
      const int id = attachment.clamp
                         ? object.clampToBody(s, body, toBullet(attachment.localPoint), toBullet(attachment.localDirection),
                                              attachment.settings)
                         : object.attachToBody(s, body, toBullet(attachment.localPoint), attachment.settings);
      if (!attachment.name.empty()) entry.ids[attachment.name] = id;
    });
  }
  for (const WinchDescription& winch : rope.winches) winches_.push_back({rope.name, winch, false});
  ropes_.push_back(std::move(entry));
}

const bullet::RopeObject* FileScene::findRope(const std::string& name) const {
  for (const RopeEntry& rope : ropes_) {
    if (rope.name == name) return rope.rope.get();
  }
  return nullptr;
}

FileScene::RopeEntry& FileScene::entry(const std::string& name) {
  for (RopeEntry& rope : ropes_) {
    if (rope.name == name) return rope;
  }
  throw std::logic_error("no rope '" + name + "'");  // the reader resolved every name
}

const btRigidBody* FileScene::findBody(const std::string& name) const {
  const auto found = bodies_.find(name);
  return found == bodies_.end() ? nullptr : found->second;
}

std::optional<int> FileScene::attachmentId(const std::string& rope, const std::string& name) const {
  for (const RopeEntry& entry : ropes_) {
    if (entry.name != rope) continue;
    const auto found = entry.ids.find(name);
    if (found == entry.ids.end()) return std::nullopt;
    for (const bullet::Attachment& attachment : entry.rope->attachments()) {
      if (attachment.id == found->second) return found->second;
    }
  }
  return std::nullopt;
}

void FileScene::applyEvent(const EventDescription& event) {
  atPath(event.path, [&] {
    switch (event.kind) {
      case EventDescription::Kind::kCut: {
        RopeEntry& cutFrom = entry(event.rope);
        RopeEntry piece;
        piece.name = event.newName;
        piece.ids = cutFrom.ids;  // ids are kept by whichever piece holds the attachment
        piece.showControlPolygon = cutFrom.showControlPolygon;
        piece.rope = cutFrom.rope->cut(parameter(*cutFrom.rope, event.s));
        ropes_.push_back(std::move(piece));
        break;
      }
      case EventDescription::Kind::kRelease: {
        const std::optional<int> id = attachmentId(event.rope, event.attachment);
        if (id) entry(event.rope).rope->removeAttachment(*id);
        break;
      }
      case EventDescription::Kind::kBodyVelocity: {
        btRigidBody* body = bodies_.at(event.body);
        body->setLinearVelocity(toBullet(event.vector));
        body->setAngularVelocity(toBullet(event.angular));
        body->activate(true);
        break;
      }
      case EventDescription::Kind::kRopeForce: {
        bullet::RopeObject& rope = *entry(event.rope).rope;
        rope.applyForce(parameter(rope, event.s), toBullet(event.vector));
        break;
      }
      case EventDescription::Kind::kRopeDistributedForce: {
        bullet::RopeObject& rope = *entry(event.rope).rope;
        rope.applyDistributedForce(parameter(rope, event.s0), parameter(rope, event.s1), toBullet(event.vector));
        break;
      }
      case EventDescription::Kind::kBodyForce: {
        btRigidBody* body = bodies_.at(event.body);
        body->applyCentralForce(toBullet(event.vector));
        body->activate(true);
        break;
      }
    }
  });
}

void FileScene::applyScript() {
  const double h = description_.timeStep;
  const double t = time();  // the step about to run covers [t, t + h]
  for (std::size_t i = 0; i < description_.events.size(); ++i) {
    const EventDescription& event = description_.events[i];
    const bool force = event.kind == EventDescription::Kind::kRopeForce ||
                       event.kind == EventDescription::Kind::kRopeDistributedForce ||
                       event.kind == EventDescription::Kind::kBodyForce;
    if (force) {
      // A force acts in the steps that start in [time, until); Bullet clears body forces after each
      // stepSimulation and a rope's load lasts one substep, so it is applied again every step.
      // A force on a rope acts once the rope is there (a cut makes a new piece).
      const bool active = t >= event.time - 0.5 * h && t < event.until - 0.5 * h;
      if (active && (!event.body.empty() || findRope(event.rope) != nullptr)) applyEvent(event);
    } else if (!eventDone_[i] && t >= event.time - 0.5 * h) {
      eventDone_[i] = true;
      applyEvent(event);
    }
  }
  for (PendingWinch& pending : winches_) {
    if (pending.started || t < pending.winch.start - 0.5 * h) continue;
    pending.started = true;
    atPath(pending.winch.path, [&] {
      bullet::RopeObject& rope = *entry(pending.rope).rope;
      if (pending.winch.restLength) {
        rope.winchTo(pending.winch.end, *pending.winch.restLength, pending.winch.speed);
      } else {
        rope.setWinchSpeed(pending.winch.end, pending.winch.speed);
      }
    });
  }
  // Loads that ramp up: their value at the step's end, so the full load is on from the ramp's end.
  for (const OwnGravity& own : ownGravity_) own.body->setGravity(own.at(static_cast<double>(steps_ + 1) * h));
  // Poses at the step's end, the time the step brings the scene to (counted, not summed: no drift).
  const double end = static_cast<double>(steps_ + 1) * h;
  for (auto& [body, keyframes] : kinematicBodies_) body->setWorldTransform(keyframePose(keyframes, end));
  for (const MovingPin& pin : movingPins_) {
    bullet::RopeObject& rope = *entry(pin.rope).rope;
    for (const bullet::Attachment& attachment : rope.attachments()) {
      if (attachment.id == pin.id) rope.setAttachmentTarget(pin.id, keyframePose(pin.keyframes, end).getOrigin());
    }
  }
}

StepMeasurements FileScene::step() {
  applyScript();
  const btScalar h = static_cast<btScalar>(description_.timeStep);
  physics_.world().stepSimulation(h, 1, h);
  ++steps_;
  StepMeasurements measurements = measure();
  for (const bullet::RopeStepRecord& record : physics_.ropes().lastReport().ropes) {
    measurements.insertions += record.insertions;
    measurements.removals += record.removals;
  }
  if (checksEnabled_) checks_.observe(*this);
  return measurements;
}

StepMeasurements FileScene::measure() const {
  StepMeasurements measurements;
  for (const RopeEntry& entry : ropes_) {
    const StepMeasurements rope = ropeMeasurements(physics_, *entry.rope);
    measurements.controlPoints += rope.controlPoints;
    measurements.maxStrain = std::max(measurements.maxStrain, rope.maxStrain);
    measurements.maxPenetration = std::max(measurements.maxPenetration.value_or(0.0), rope.maxPenetration.value_or(0.0));
    measurements.maxSelfOverlap = rope.maxSelfOverlap;
  }
  for (const CheckResult& check : checks_.results()) measurements.series.emplace_back("check." + check.name, check.latest);
  return measurements;
}

void FileScene::draw(render::Scene& scene) const {
  physics_.draw(scene);
  for (const RopeEntry& entry : ropes_) drawRope(scene, *entry.rope, entry.showControlPolygon);
}

std::optional<render::Camera> FileScene::camera() const {
  std::optional<render::Camera> camera = description_.camera;
  const bullet::RopeObject* rope = findRope(description_.cameraFollow);
  if (!camera || rope == nullptr) return camera;
  // The mean of 65 points along the rope, as the pile scene's camera follows its rope.
  const Rod& rod = rope->rod();
  constexpr int kSamples = 64;
  Vec3 mean = Vec3::Zero();
  for (int i = 0; i <= kSamples; ++i) {
    mean += rod.position(std::min(rod.endParameter(),
                                  rod.beginParameter() + (rod.endParameter() - rod.beginParameter()) * i / kSamples));
  }
  mean /= kSamples + 1;
  const Vec3 offset = camera->eye - camera->target;
  camera->target = mean;
  camera->eye = mean + offset;
  return camera;
}

void FileScene::appendState(std::vector<double>& state) const { appendWorldState(physics_, state); }

}  // namespace rope::demos
