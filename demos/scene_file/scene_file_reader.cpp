// SPDX-License-Identifier: MIT
#include "demos/scene_file/scene_file_reader.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

#include "demos/scene_file/bullet_file_import.h"
#include "demos/scene_file/json_fields.h"
#include "demos/scene_file/obj_mesh.h"
#include "demos/scenes/physics_world.h"
#include "rope/common/error.h"

namespace rope::demos {

namespace {

using nlohmann::json;

// Runs `build`; a rope::InvalidArgument it throws for parameter "<prefix>.<key>" (the library's
// validate() names fields like "settings.radius") becomes a SceneFileError at fields.pathOf(key),
// with the value as the file writes it, so the ranges are the library's and are not repeated here.
void withLibraryChecks(const JsonFields& fields, const std::string& prefix, const std::function<void()>& build) {
  try {
    build();
  } catch (const InvalidArgument& error) {
    const std::string& parameter = error.parameter();
    std::string key = parameter;
    if (!prefix.empty() && key.rfind(prefix + ".", 0) == 0) key = key.substr(prefix.size() + 1);
    auto [value, reason] = splitLibraryError(error);
    const std::string base = key.substr(0, key.find_first_of(".["));
    if (fields.has(base)) {
      const std::string tail = key.substr(base.size());
      value = tail.empty() ? jsonText(fields.at(base)) : value;
    }
    throw SceneFileError(fields.pathOf(key), value, reason);
  }
}

Eigen::Vector4d readRotation(const JsonFields& fields, const std::string& key) {
  if (!fields.has(key)) return Eigen::Vector4d(0.0, 0.0, 0.0, 1.0);
  const json& value = fields.at(key);
  const std::string path = fields.pathOf(key);
  if (!value.is_array() || value.size() != 4) {
    throw SceneFileError(path, jsonText(value), "must be a quaternion [x, y, z, w]");
  }
  Eigen::Vector4d q;
  for (int i = 0; i < 4; ++i) q[i] = jsonNumber(value[i], path + "[" + std::to_string(i) + "]");
  const double norm = q.norm();
  if (std::abs(norm - 1.0) > 1e-6) throw SceneFileError(path, jsonText(value), "must be a unit quaternion (|q| = 1)");
  return q;
}

std::vector<Keyframe> readKeyframes(const JsonFields& fields, bool withRotation) {
  std::vector<Keyframe> keyframes;
  for (const auto& [item, path] : fields.array("keyframes")) {
    const JsonFields frame(*item, path, "keyframe");
    Keyframe keyframe;
    keyframe.time = frame.number("time");
    if (keyframe.time < 0.0) throw SceneFileError(frame.pathOf("time"), jsonText(frame.at("time")), "must be >= 0");
    if (!keyframes.empty() && !(keyframe.time > keyframes.back().time)) {
      throw SceneFileError(frame.pathOf("time"), jsonText(frame.at("time")), "must be later than the keyframe before");
    }
    keyframe.position = frame.vec3("position");
    if (!withRotation && frame.has("rotation")) {
      throw SceneFileError(frame.pathOf("rotation"), "", "a pin's keyframes have positions only");
    }
    keyframe.rotation = readRotation(frame, "rotation");
    keyframe.interpolation = frame.choice("interpolation", {"linear", "smoothstep"}, "linear") == "smoothstep"
                                 ? Keyframe::Interpolation::kSmoothstep
                                 : Keyframe::Interpolation::kLinear;
    keyframes.push_back(keyframe);
  }
  return keyframes;
}

RopeParameter readParameter(const JsonFields& fields, const std::string& key) {
  const json& value = fields.at(key);
  RopeParameter s;
  if (value.is_string()) {
    const std::string word = value.get<std::string>();
    if (word == "begin") {
      s.kind = RopeParameter::Kind::kBegin;
    } else if (word == "end") {
      s.kind = RopeParameter::Kind::kEnd;
    } else {
      throw SceneFileError(fields.pathOf(key), jsonText(value), "must be a number (m) or \"begin\" or \"end\"");
    }
    return s;
  }
  s.value = jsonNumber(value, fields.pathOf(key));
  if (s.value < 0.0) throw SceneFileError(fields.pathOf(key), jsonText(value), "must be >= 0");
  return s;
}

// "derived" or a number.
double numberOrDerived(const JsonFields& fields, const std::string& key, double fallback, double derived) {
  if (fields.has(key) && fields.at(key).is_string()) {
    if (fields.at(key).get<std::string>() == "derived") return derived;
    throw SceneFileError(fields.pathOf(key), jsonText(fields.at(key)), "must be a number or \"derived\"");
  }
  return fields.number(key, fallback);
}

void requireUniqueName(std::set<std::string>& names, const JsonFields& fields, const std::string& what) {
  const std::string name = fields.string("name");
  if (name.empty()) throw SceneFileError(fields.pathOf("name"), "\"\"", "must not be empty");
  if (!names.insert(name).second) {
    throw SceneFileError(fields.pathOf("name"), jsonText(fields.at("name")), "another " + what + " has this name");
  }
}

void readRopeSettings(const JsonFields& fields, RodSettings& rod, bullet::BulletRopeSettings& bridge) {
  rod.restLength = fields.number("restLength", rod.restLength);
  rod.radius = fields.number("radius", rod.radius);
  rod.linearDensity = numberOrDerived(fields, "linearDensity", rod.linearDensity, RodSettings::kDerived);
  rod.materialDensity = fields.number("materialDensity", rod.materialDensity);
  rod.youngsModulus = fields.number("youngsModulus", rod.youngsModulus);
  rod.bendingStiffness = numberOrDerived(fields, "bendingStiffness", rod.bendingStiffness, RodSettings::kDerived);
  rod.massDamping = fields.number("massDamping", rod.massDamping);
  rod.stiffnessDamping = fields.number("stiffnessDamping", rod.stiffnessDamping);
  rod.materialDamping = fields.number("materialDamping", rod.materialDamping);
  rod.gravity = fields.vec3("gravity", rod.gravity);
  rod.timeIntegrator = fields.choice("timeIntegrator", {"bdf2", "backwardEuler"}, "bdf2") == "backwardEuler"
                           ? TimeIntegrator::kBackwardEuler
                           : TimeIntegrator::kBdf2;
  rod.degree = fields.integer("degree", rod.degree);
  rod.initialControlPoints = fields.integer("initialControlPoints", rod.initialControlPoints);
  rod.stretchingQuadrature = fields.choice("stretchingQuadrature", {"lockingFree", "exact"}, "lockingFree") == "exact"
                                 ? StretchingQuadrature::kExact
                                 : StretchingQuadrature::kLockingFree;
  rod.adaptive = fields.boolean("adaptive", rod.adaptive);
  rod.minControlPoints = fields.integer("minControlPoints", rod.minControlPoints);
  rod.maxControlPoints = fields.integer("maxControlPoints", rod.maxControlPoints);
  rod.insertAngle = fields.number("insertAngle", rod.insertAngle);
  rod.removeAngle = fields.number("removeAngle", rod.removeAngle);
  rod.removalErrorBound = fields.number("removalErrorBound", rod.removalErrorBound);
  rod.removalVelocityErrorBound = fields.number("removalVelocityErrorBound", rod.removalVelocityErrorBound);
  const std::string criterion =
      fields.choice("removalCriterion", {"polygon", "mechanical", "mechanicalOutOfContact"}, "mechanicalOutOfContact");
  rod.removalCriterion = criterion == "polygon"      ? RemovalCriterion::kPolygon
                         : criterion == "mechanical" ? RemovalCriterion::kMechanical
                                                     : RemovalCriterion::kMechanicalOutOfContact;
  rod.removalRelativeError = fields.number("removalRelativeError", rod.removalRelativeError);
  rod.minKnotSpacing = fields.number("minKnotSpacing", rod.minKnotSpacing);

  bridge.lineContactStiffness = fields.number("lineContactStiffness", bridge.lineContactStiffness);
  bridge.lineContactDamping = fields.number("lineContactDamping", bridge.lineContactDamping);
  bridge.lineSpeculativeDamping = fields.number("lineSpeculativeDamping", bridge.lineSpeculativeDamping);
  bridge.contactQuadraturePoints = fields.integer("contactQuadraturePoints", bridge.contactQuadraturePoints);
  bridge.concentratedContactRatio = fields.number("concentratedContactRatio", bridge.concentratedContactRatio);
  bridge.friction = fields.number("friction", bridge.friction);
  bridge.frictionVelocity = fields.number("frictionVelocity", bridge.frictionVelocity);
  bridge.gravitySource = fields.choice("gravitySource", {"world", "rod"}, "world") == "rod"
                             ? bullet::BulletRopeSettings::GravitySource::kRod
                             : bullet::BulletRopeSettings::GravitySource::kWorld;
  bridge.gravityScale = fields.number("gravityScale", bridge.gravityScale);
  bridge.fluidDensity = fields.number("fluidDensity", bridge.fluidDensity);
  bridge.normalDragCoefficient = fields.number("normalDragCoefficient", bridge.normalDragCoefficient);
  bridge.tangentialDragCoefficient = fields.number("tangentialDragCoefficient", bridge.tangentialDragCoefficient);
  const Vec3 wind = fields.vec3("windVelocity", Vec3(bridge.windVelocity.x(), bridge.windVelocity.y(), bridge.windVelocity.z()));
  bridge.windVelocity = btVector3(static_cast<btScalar>(wind.x()), static_cast<btScalar>(wind.y()), static_cast<btScalar>(wind.z()));
  bridge.contactStiffness = fields.number("contactStiffness", bridge.contactStiffness);
  bridge.contactDamping = fields.number("contactDamping", bridge.contactDamping);
  bridge.speculativeDamping = fields.number("speculativeDamping", bridge.speculativeDamping);
  bridge.capsulesPerSpan = fields.integer("capsulesPerSpan", bridge.capsulesPerSpan);
  bridge.speculativeMargin = fields.number("speculativeMargin", bridge.speculativeMargin);
  bridge.initialPredictionTime = fields.number("initialPredictionTime", bridge.initialPredictionTime);
  bridge.bodyStabilityFactor = fields.number("bodyStabilityFactor", bridge.bodyStabilityFactor);
  bridge.collisionGroup = fields.integer("collisionGroup", bridge.collisionGroup);
  bridge.collisionMask = fields.integer("collisionMask", bridge.collisionMask);
  bridge.selfContact = fields.boolean("selfContact", bridge.selfContact);
  bridge.selfContactExclusion = numberOrDerived(fields, "selfContactExclusion", bridge.selfContactExclusion,
                                                bullet::BulletRopeSettings::kDerivedExclusion);
  withLibraryChecks(fields, "settings", [&] {
    rod.validate();
    bridge.validate();
  });
}

void requirePositiveKey(const JsonFields& fields, const std::string& key, double value) {
  if (!(value > 0.0)) throw SceneFileError(fields.pathOf(key), jsonText(fields.at(key)), "must be > 0");
}

void requireNonNegativeKey(const JsonFields& fields, const std::string& key, double value) {
  if (fields.has(key) && value < 0.0) throw SceneFileError(fields.pathOf(key), jsonText(fields.at(key)), "must be >= 0");
}

// A key that the object's kind does not use is an error, not silently ignored.
void forbid(const JsonFields& fields, const std::vector<std::string>& keys, const std::string& kind) {
  for (const std::string& key : keys) {
    if (fields.has(key)) throw SceneFileError(fields.pathOf(key), "", "does not apply to " + kind);
  }
}

// A file a scene file names: relative to the scene file's directory.
std::string resolvePath(const std::string& path, const std::string& directory) {
  return std::filesystem::path(path).is_absolute() || directory.empty() ? path
                                                                         : (std::filesystem::path(directory) / path).string();
}

// The vertices and triangles of a body's OBJ file (relative paths: to the scene file's directory).
void readBodyMesh(const JsonFields& fields, const std::string& directory, BodyDescription& body) {
  body.mesh = fields.string("mesh");
  body.meshType = fields.choice("meshType", {"convexHull", "triangleMesh"}, "convexHull") == "triangleMesh"
                      ? BodyDescription::MeshType::kTriangleMesh
                      : BodyDescription::MeshType::kConvexHull;
  body.scale = fields.number("scale", 1.0);
  requirePositiveKey(fields, "scale", body.scale);
  body.margin = fields.number("margin", 0.0);
  requireNonNegativeKey(fields, "margin", body.margin);
  if (body.meshType == BodyDescription::MeshType::kTriangleMesh) forbid(fields, {"margin"}, "a triangle mesh");
  if (body.meshType == BodyDescription::MeshType::kTriangleMesh && body.motion != BodyDescription::Motion::kStatic) {
    throw SceneFileError(fields.pathOf("meshType"), jsonText(fields.at("meshType")),
                         "a triangle mesh must be static (Bullet's btBvhTriangleMeshShape); use \"convexHull\"");
  }
  const std::string resolved = resolvePath(body.mesh, directory);
  ObjMesh mesh;
  try {
    mesh = readObjMesh(resolved);
  } catch (const std::runtime_error& error) {
    throw SceneFileError(fields.pathOf("mesh"), jsonText(fields.at("mesh")), error.what());
  }
  for (Vec3& vertex : mesh.vertices) vertex *= body.scale;
  body.meshVertices = std::move(mesh.vertices);
  body.meshTriangles = std::move(mesh.triangles);
}

// A .bullet file: imported once into a scratch world now, so that a file that is not one stops
// before simulating and the names of its bodies are known to attachments and checks.
void readBulletFile(const JsonFields& fields, const std::string& directory, BodyDescription& body) {
  body.file = resolvePath(fields.string("file"), directory);
  try {
    PhysicsWorld scratch;
    const BulletFileImport import(scratch.world(), body.file);
    for (const auto& [name, rigidBody] : import.bodies()) body.importedBodies.push_back(name);
  } catch (const std::runtime_error& error) {
    throw SceneFileError(fields.pathOf("file"), jsonText(fields.at("file")), error.what());
  }
}

// The geometry of a body of `shape` (not a bulletFile): its sizes, its mesh or its plane; the keys
// of the other shapes are errors.
void readShapeGeometry(const JsonFields& fields, const std::string& shape, const std::string& directory,
                       BodyDescription& body) {
  const std::string kind = "a " + shape;
  if (shape != "mesh") forbid(fields, {"mesh", "meshType", "scale", "margin"}, kind);
  if (shape == "cylinder" || shape == "capsule") {
    const std::string axis = fields.choice("axis", {"x", "y", "z"}, "y");
    body.axis = axis == "x" ? 0 : axis == "y" ? 1 : 2;
  } else {
    forbid(fields, {"axis"}, kind);
  }
  if (shape == "mesh") {
    body.shape = BodyDescription::Shape::kMesh;
    forbid(fields, {"halfExtents", "radius", "height", "normal", "offset"}, kind);
    readBodyMesh(fields, directory, body);
  } else if (shape == "box" || shape == "cylinder") {
    body.shape = shape == "box" ? BodyDescription::Shape::kBox : BodyDescription::Shape::kCylinder;
    forbid(fields, {"radius", "height", "normal", "offset"}, kind);
    body.halfExtents = fields.vec3("halfExtents");
    for (int i = 0; i < 3; ++i) {
      if (!(body.halfExtents[i] > 0.0)) {
        throw SceneFileError(fields.pathOf("halfExtents") + "[" + std::to_string(i) + "]", jsonText(fields.at("halfExtents")[i]),
                             "must be > 0");
      }
    }
  } else if (shape == "sphere" || shape == "capsule") {
    body.shape = shape == "sphere" ? BodyDescription::Shape::kSphere : BodyDescription::Shape::kCapsule;
    forbid(fields, {"halfExtents", "normal", "offset"}, kind);
    if (shape == "sphere") forbid(fields, {"height"}, kind);
    body.radius = fields.number("radius");
    requirePositiveKey(fields, "radius", body.radius);
    if (shape == "capsule") {
      body.height = fields.number("height");
      requireNonNegativeKey(fields, "height", body.height);
    }
  } else {
    body.shape = BodyDescription::Shape::kPlane;
    forbid(fields, {"halfExtents", "radius", "height", "position", "rotation", "keyframes", "mass", "linearVelocity",
                    "angularVelocity"},
           kind);
    if (body.motion != BodyDescription::Motion::kStatic) {
      throw SceneFileError(fields.pathOf("motion"), jsonText(fields.at("motion")), "a plane must be static");
    }
    body.normal = fields.vec3("normal", body.normal);
    if (!(body.normal.norm() > 0.0)) throw SceneFileError(fields.pathOf("normal"), jsonText(fields.at("normal")), "must not be zero");
    body.normal.normalize();
    body.offset = fields.number("offset", 0.0);
  }
}

BodyDescription readBody(const JsonFields& fields, const std::string& directory) {
  BodyDescription body;
  body.name = fields.string("name");
  const std::string shape = fields.choice("shape", {"box", "sphere", "capsule", "cylinder", "plane", "mesh", "bulletFile"}, "");
  if (shape != "bulletFile") forbid(fields, {"file"}, "a " + shape);
  if (shape == "bulletFile") {
    // The file's bodies keep their own shapes, masses, poses and materials.
    forbid(fields, {"motion", "halfExtents", "radius", "height", "axis", "normal", "offset", "mesh", "meshType", "scale",
                    "margin", "mass", "position", "rotation", "linearVelocity", "angularVelocity", "friction",
                    "restitution", "canSleep", "gravity", "gravityRampTime", "keyframes"},
           "a bulletFile (its bodies are as the file has them)");
    body.shape = BodyDescription::Shape::kBulletFile;
    readBulletFile(fields, directory, body);
    return body;
  }
  const std::string motion = fields.choice("motion", {"static", "kinematic", "dynamic"}, "static");
  body.motion = motion == "dynamic" ? BodyDescription::Motion::kDynamic
                : motion == "kinematic" ? BodyDescription::Motion::kKinematic
                                        : BodyDescription::Motion::kStatic;
  readShapeGeometry(fields, shape, directory, body);
  if (body.motion == BodyDescription::Motion::kDynamic) {
    body.mass = fields.number("mass");
    requirePositiveKey(fields, "mass", body.mass);
  } else if (fields.has("mass")) {
    throw SceneFileError(fields.pathOf("mass"), jsonText(fields.at("mass")), "only a dynamic body has a mass");
  }
  if (body.motion != BodyDescription::Motion::kDynamic) {
    forbid(fields, {"linearVelocity", "angularVelocity", "canSleep", "gravity", "gravityRampTime"}, "a " + motion + " body");
  }
  if (fields.has("gravity")) body.gravity = fields.vec3("gravity");
  if (fields.has("gravityRampTime") && !body.gravity) {
    throw SceneFileError(fields.pathOf("gravityRampTime"), jsonText(fields.at("gravityRampTime")), "needs the body's own 'gravity'");
  }
  body.gravityRampTime = fields.number("gravityRampTime", 0.0);
  requireNonNegativeKey(fields, "gravityRampTime", body.gravityRampTime);
  body.canSleep = fields.boolean("canSleep", false);
  if (body.motion != BodyDescription::Motion::kKinematic) forbid(fields, {"keyframes"}, "a " + motion + " body (only kinematic bodies follow keyframes)");
  body.position = fields.vec3("position", body.position);
  body.rotation = readRotation(fields, "rotation");
  body.linearVelocity = fields.vec3("linearVelocity", body.linearVelocity);
  body.angularVelocity = fields.vec3("angularVelocity", body.angularVelocity);
  body.friction = fields.number("friction", body.friction);
  requireNonNegativeKey(fields, "friction", body.friction);
  body.restitution = fields.number("restitution", body.restitution);
  requireNonNegativeKey(fields, "restitution", body.restitution);
  body.keyframes = readKeyframes(fields, true);
  return body;
}

RopeShapeDescription readRopeShape(const JsonFields& fields) {
  RopeShapeDescription shape;
  const std::string type = fields.choice("type", {"segment", "polyline", "helix", "coil"}, "");
  const std::string kind = "a " + type;
  auto restShape = [&] {
    return fields.choice("restShape", {"scaled", "asGiven"}, "scaled") == "asGiven" ? Rod::RestShape::kAsGiven
                                                                                     : Rod::RestShape::kScaledToRestLength;
  };
  if (type == "segment") {
    shape.kind = RopeShapeDescription::Kind::kSegment;
    forbid(fields, {"points", "restShape", "center", "radius", "pitch", "turns", "pointsPerTurn", "tilt"}, kind);
    shape.from = fields.vec3("from");
    shape.to = fields.vec3("to");
    if (shape.from == shape.to) throw SceneFileError(fields.pathOf("to"), jsonText(fields.at("to")), "must differ from 'from'");
  } else if (type == "polyline") {
    shape.kind = RopeShapeDescription::Kind::kPolyline;
    forbid(fields, {"from", "to", "center", "radius", "pitch", "turns", "pointsPerTurn", "tilt"}, kind);
    for (const auto& [item, path] : fields.array("points")) shape.points.push_back(jsonVec3(*item, path));
    if (!fields.has("points")) fields.at("points");
    shape.restShape = restShape();
  } else if (type == "helix") {
    shape.kind = RopeShapeDescription::Kind::kHelix;
    forbid(fields, {"from", "to", "points", "tilt"}, kind);
    shape.center = fields.vec3("center", shape.center);
    shape.radius = fields.number("radius");
    requirePositiveKey(fields, "radius", shape.radius);
    shape.pitch = fields.number("pitch");
    requireNonNegativeKey(fields, "pitch", shape.pitch);
    shape.turns = fields.number("turns");
    requirePositiveKey(fields, "turns", shape.turns);
    shape.pointsPerTurn = fields.integer("pointsPerTurn", shape.pointsPerTurn);
    if (shape.pointsPerTurn < 4) throw SceneFileError(fields.pathOf("pointsPerTurn"), jsonText(fields.at("pointsPerTurn")), "must be >= 4");
    shape.restShape = restShape();
  } else {
    shape.kind = RopeShapeDescription::Kind::kCoil;
    forbid(fields, {"from", "to", "points", "restShape", "turns", "pointsPerTurn"}, kind);
    shape.center = fields.vec3("center", shape.center);
    shape.radius = fields.number("radius");
    shape.pitch = fields.number("pitch");
    shape.tilt = fields.number("tilt", 0.0);
  }
  return shape;
}

void readRopeItems(const JsonFields& rope, RopeDescription& description) {
  std::set<std::string> names;
  auto optionalName = [&](const JsonFields& fields) {
    if (!fields.has("name")) return std::string();
    requireUniqueName(names, fields, "pin or attachment of this rope");
    return fields.string("name");
  };
  for (const auto& [item, path] : rope.array("pins")) {
    const JsonFields fields(*item, path, "pin");
    PinDescription pin;
    pin.path = path;
    pin.name = optionalName(fields);
    pin.s = readParameter(fields, "s");
    if (fields.has("target")) pin.target = fields.vec3("target");
    pin.keyframes = readKeyframes(fields, false);
    if (pin.target && !pin.keyframes.empty()) throw SceneFileError(fields.pathOf("keyframes"), "", "give either a target or keyframes");
    description.pins.push_back(pin);
  }
  for (const char* list : {"attachments", "clamps"}) {
    const bool clamp = std::string(list) == "clamps";
    for (const auto& [item, path] : rope.array(list)) {
      const JsonFields fields(*item, path, clamp ? "clamp" : "attachment");
      AttachmentDescription attachment;
      attachment.path = path;
      attachment.name = optionalName(fields);
      attachment.clamp = clamp;
      attachment.s = readParameter(fields, "s");
      attachment.body = fields.string("body");
      attachment.localPoint = fields.vec3("localPoint", attachment.localPoint);
      attachment.settings.stiffness = fields.number("stiffness", attachment.settings.stiffness);
      attachment.settings.damping = fields.number("damping", attachment.settings.damping);
      if (clamp) {
        attachment.localDirection = fields.vec3("localDirection", attachment.localDirection);
        if (!(attachment.localDirection.norm() > 0.0)) {
          throw SceneFileError(fields.pathOf("localDirection"), jsonText(fields.at("localDirection")), "must not be zero");
        }
        attachment.settings.angularStiffness = fields.number("angularStiffness", attachment.settings.angularStiffness);
        attachment.settings.angularDamping = fields.number("angularDamping", attachment.settings.angularDamping);
      }
      withLibraryChecks(fields, "attachment", [&] { attachment.settings.validate(); });
      description.attachments.push_back(attachment);
    }
  }
  for (const auto& [item, path] : rope.array("winches")) {
    const JsonFields fields(*item, path, "winch");
    WinchDescription winch;
    winch.path = path;
    winch.end = fields.choice("end", {"begin", "end"}, "end") == "begin" ? bullet::RopeEnd::kBegin : bullet::RopeEnd::kEnd;
    winch.speed = fields.number("speed");
    if (fields.has("restLength")) {
      winch.restLength = fields.number("restLength");
      requirePositiveKey(fields, "restLength", *winch.restLength);
      requirePositiveKey(fields, "speed", winch.speed);
    }
    if (std::abs(winch.speed) > bullet::kMaxWinchSpeed) {
      throw SceneFileError(fields.pathOf("speed"), jsonText(fields.at("speed")), "must be at most 100 m/s in size");
    }
    winch.start = fields.number("start", 0.0);
    requireNonNegativeKey(fields, "start", winch.start);
    description.winches.push_back(winch);
  }
}

RopeDescription readRope(const JsonFields& fields) {
  RopeDescription rope;
  rope.name = fields.string("name");
  if (fields.has("settings")) {
    readRopeSettings(JsonFields(fields.at("settings"), fields.pathOf("settings"), "rope.settings"), rope.rod, rope.bridge);
  }
  rope.shape = readRopeShape(JsonFields(fields.at("shape"), fields.pathOf("shape"), "rope.shape"));
  rope.showControlPolygon = fields.boolean("showControlPolygon", false);
  readRopeItems(fields, rope);
  return rope;
}

double readTime(const JsonFields& fields, const std::string& key, double fallback) {
  const double time = fields.number(key, fallback);
  requireNonNegativeKey(fields, key, time);
  return time;
}

struct Names {
  std::set<std::string> bodies, ropes;
};

void requireRope(const Names& names, const JsonFields& fields) {
  const std::string rope = fields.string("rope");
  if (names.ropes.count(rope) == 0) throw SceneFileError(fields.pathOf("rope"), jsonText(fields.at("rope")), "no rope of that name");
}

void requireBody(const Names& names, const JsonFields& fields) {
  const std::string body = fields.string("body");
  if (names.bodies.count(body) == 0) throw SceneFileError(fields.pathOf("body"), jsonText(fields.at("body")), "no body of that name");
}

// A distributed force's stretch of rope: s0 and s1 ("begin" and "end" when left out), s1 after s0
// where both are numbers (the rope's own range is checked once it is built).
void readForceStretch(const JsonFields& fields, EventDescription& event) {
  if (fields.has("s0")) event.s0 = readParameter(fields, "s0");
  if (fields.has("s1")) event.s1 = readParameter(fields, "s1");
  const bool numbers = event.s0.kind == RopeParameter::Kind::kValue && event.s1.kind == RopeParameter::Kind::kValue;
  const bool backwards = event.s0.kind == RopeParameter::Kind::kEnd || event.s1.kind == RopeParameter::Kind::kBegin;
  if ((numbers && !(event.s1.value > event.s0.value)) || backwards) {
    const std::string key = fields.has("s1") ? "s1" : "s0";
    throw SceneFileError(fields.pathOf(key), jsonText(fields.at(key)), "must give s1 > s0");
  }
}

EventDescription readEvent(const JsonFields& fields, Names& names) {
  EventDescription event;
  event.path = fields.path();
  const std::string type = fields.choice("type", {"cut", "force", "distributedForce", "velocity", "release"}, "");
  event.time = readTime(fields, "time", 0.0);
  if (!fields.has("time")) fields.at("time");
  const std::string kind = "a " + type + " event";
  if (type != "distributedForce") forbid(fields, {"s0", "s1", "forcePerLength"}, kind);
  if (type == "cut") {
    event.kind = EventDescription::Kind::kCut;
    forbid(fields, {"until", "body", "attachment", "force", "linearVelocity", "angularVelocity"}, kind);
    requireRope(names, fields);
    event.rope = fields.string("rope");
    event.s = readParameter(fields, "s");
    event.newName = fields.string("name");
    if (!names.ropes.insert(event.newName).second && !event.newName.empty()) {
      throw SceneFileError(fields.pathOf("name"), jsonText(fields.at("name")), "another rope has this name");
    }
  } else if (type == "force" || type == "distributedForce") {
    forbid(fields, {"attachment", "linearVelocity", "angularVelocity", "name"}, kind);
    event.until = fields.number("until");
    if (!(event.until > event.time)) throw SceneFileError(fields.pathOf("until"), jsonText(fields.at("until")), "must be later than 'time'");
    if (type == "distributedForce") {
      event.kind = EventDescription::Kind::kRopeDistributedForce;
      forbid(fields, {"body", "s", "force"}, kind);
      event.vector = fields.vec3("forcePerLength");
      requireRope(names, fields);
      event.rope = fields.string("rope");
      readForceStretch(fields, event);
    } else if (fields.has("rope")) {
      event.vector = fields.vec3("force");
      event.kind = EventDescription::Kind::kRopeForce;
      forbid(fields, {"body"}, "a force on a rope");
      requireRope(names, fields);
      event.rope = fields.string("rope");
      event.s = readParameter(fields, "s");
    } else {
      event.vector = fields.vec3("force");
      event.kind = EventDescription::Kind::kBodyForce;
      forbid(fields, {"s"}, "a force on a body");
      requireBody(names, fields);
      event.body = fields.string("body");
    }
  } else if (type == "velocity") {
    event.kind = EventDescription::Kind::kBodyVelocity;
    forbid(fields, {"until", "rope", "attachment", "s", "force", "name"}, kind);
    requireBody(names, fields);
    event.body = fields.string("body");
    event.vector = fields.vec3("linearVelocity", Vec3::Zero());
    event.angular = fields.vec3("angularVelocity", Vec3::Zero());
  } else {
    event.kind = EventDescription::Kind::kRelease;
    forbid(fields, {"until", "body", "s", "force", "linearVelocity", "angularVelocity", "name"}, kind);
    requireRope(names, fields);
    event.rope = fields.string("rope");
    event.attachment = fields.string("attachment");
  }
  return event;
}

// A position check: a rope point (rope and s) or a body point, in a box or near a target, over the
// window or at one time.
void readPositionCheck(const JsonFields& fields, CheckDescription& check) {
  const std::string kind = "a position check";
  check.kind = CheckDescription::Kind::kPosition;
  forbid(fields, {"attachment", "winch", "mode", "min"}, kind);
  if (check.rope.empty() == check.body.empty()) throw SceneFileError(fields.path(), "", "a position check needs either 'rope' (with 's') or 'body'");
  if (!check.rope.empty()) {
    forbid(fields, {"localPoint"}, "the position of a rope point");
    check.s = readParameter(fields, "s");
  } else {
    forbid(fields, {"s"}, "the position of a body");
    check.localPoint = fields.vec3("localPoint", Vec3::Zero());
  }
  if (fields.has("at")) {
    check.at = readTime(fields, "at", 0.0);
    forbid(fields, {"from", "to"}, "a position check at one time ('at')");
  }
  if (fields.has("box") == fields.has("target")) throw SceneFileError(fields.path(), "", "a position check needs either 'box' or 'target'");
  if (fields.has("box")) {
    forbid(fields, {"max"}, "a position check in a box");
    const JsonFields box(fields.at("box"), fields.pathOf("box"), "box");
    check.boxMin = box.vec3("min");
    check.boxMax = box.vec3("max");
    for (int i = 0; i < 3; ++i) {
      if (!((*check.boxMax)[i] >= (*check.boxMin)[i])) {
        throw SceneFileError(box.pathOf("max") + "[" + std::to_string(i) + "]", jsonText(box.at("max")[i]), "must be >= min");
      }
    }
  } else {
    check.target = fields.vec3("target");
    if (!check.max) fields.at("max");
    requireNonNegativeKey(fields, "max", *check.max);
  }
}

CheckDescription readCheck(const JsonFields& fields, const Names& names, std::set<std::string>& checkNames) {
  CheckDescription check;
  check.path = fields.path();
  requireUniqueName(checkNames, fields, "check");
  check.name = fields.string("name");
  const std::string type =
      fields.choice("type", {"penetration", "contact", "tension", "position", "slip", "health", "knotLength"}, "");
  const std::string kind = "a " + type + " check";
  check.from = readTime(fields, "from", 0.0);
  check.to = readTime(fields, "to", 1e300);
  if (!(check.to > check.from)) throw SceneFileError(fields.pathOf("to"), jsonText(fields.at("to")), "must be later than 'from'");
  if (fields.has("rope")) requireRope(names, fields);
  if (fields.has("body")) requireBody(names, fields);
  check.rope = fields.string("rope", "");
  check.body = fields.string("body", "");
  auto bound = [&](const std::string& key) -> std::optional<double> {
    if (!fields.has(key)) return std::nullopt;
    return fields.number(key);
  };
  check.min = bound("min");
  check.max = bound("max");
  auto needRope = [&] { if (check.rope.empty()) fields.at("rope"); };
  auto needMax = [&] {
    if (!check.max) fields.at("max");
    requireNonNegativeKey(fields, "max", *check.max);
  };
  if (type == "penetration" || type == "knotLength") {
    check.kind = type == "penetration" ? CheckDescription::Kind::kPenetration : CheckDescription::Kind::kKnotLength;
    forbid(fields, {"at", "attachment", "s", "winch", "mode", "min", "box", "target", "localPoint"}, kind);
    if (type == "knotLength") forbid(fields, {"body"}, kind);
    needRope();
    needMax();
  } else if (type == "contact") {
    check.kind = CheckDescription::Kind::kContact;
    forbid(fields, {"at", "attachment", "s", "winch", "min", "max", "box", "target", "localPoint"}, kind);
    needRope();
    if (check.body.empty()) fields.at("body");
    check.never = fields.choice("mode", {"stays", "never"}, "") == "never";
  } else if (type == "tension") {
    check.kind = CheckDescription::Kind::kTension;
    forbid(fields, {"at", "body", "mode", "box", "target", "localPoint"}, kind);
    needRope();
    const int places = fields.has("s") + fields.has("attachment") + fields.has("winch");
    if (places != 1) throw SceneFileError(fields.path(), "", "a tension check needs exactly one of 's', 'attachment', 'winch'");
    if (fields.has("s")) check.s = readParameter(fields, "s");
    check.attachment = fields.string("attachment", "");
    if (fields.has("winch")) {
      check.winch = fields.choice("winch", {"begin", "end"}, "") == "begin" ? bullet::RopeEnd::kBegin : bullet::RopeEnd::kEnd;
    }
    if (!check.min && !check.max) throw SceneFileError(fields.path(), "", "a tension check needs 'min', 'max' or both");
    if (check.min && check.max && *check.min > *check.max) {
      throw SceneFileError(fields.pathOf("max"), jsonText(fields.at("max")), "must be >= 'min'");
    }
  } else if (type == "position") {
    readPositionCheck(fields, check);
  } else if (type == "slip") {
    check.kind = CheckDescription::Kind::kSlip;
    forbid(fields, {"at", "attachment", "s", "winch", "mode", "min", "box", "target"}, kind);
    needRope();
    if (check.body.empty()) fields.at("body");
    check.localPoint = fields.vec3("localPoint", Vec3::Zero());
    needMax();
  } else {
    check.kind = CheckDescription::Kind::kHealth;
    forbid(fields, {"at", "body", "attachment", "s", "winch", "mode", "min", "max", "box", "target", "localPoint"}, kind);
  }
  return check;
}

render::Camera readCamera(const JsonFields& fields) {
  render::Camera camera;
  camera.eye = fields.vec3("eye");
  camera.target = fields.vec3("target");
  camera.up = fields.vec3("up", camera.up);
  camera.verticalFovDegrees = fields.number("verticalFovDegrees", camera.verticalFovDegrees);
  withLibraryChecks(fields, "camera", [&] { camera.validate(); });
  return camera;
}

}  // namespace

SceneOverride parseSceneOverride(const std::string& text) {
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw SceneFileError("--set", text, "expected PATH=VALUE, e.g. ropes[0].settings.youngsModulus=1e8");
  }
  return {text.substr(0, equals), text.substr(equals + 1)};
}

void applySceneOverrides(nlohmann::json& document, const std::vector<SceneOverride>& overrides) {
  for (const SceneOverride& change : overrides) {
    json value;
    try {
      value = json::parse(change.value);
    } catch (const json::parse_error&) {
      value = change.value;  // plain text: a string
    }
    json* node = &document;
    std::string walked;
    std::size_t i = 0;
    const std::string& path = change.path;
    while (i < path.size()) {
      if (path[i] == '[') {
        const std::size_t close = path.find(']', i);
        std::size_t index = 0;
        try {
          index = std::stoul(path.substr(i + 1, close - i - 1));
        } catch (const std::exception&) {
          throw SceneFileError("--set " + path, "", "bad index after '" + walked + "'");
        }
        if (close == std::string::npos || !node->is_array() || index >= node->size()) {
          throw SceneFileError("--set " + path, "", "'" + walked + "' has no element " + path.substr(i, close - i + 1));
        }
        walked += path.substr(i, close - i + 1);
        node = &(*node)[index];
        i = close + 1;
      } else {
        if (path[i] == '.') ++i;
        const std::size_t end = path.find_first_of(".[", i);
        const std::string key = path.substr(i, end == std::string::npos ? std::string::npos : end - i);
        if (key.empty() || !node->is_object()) {
          throw SceneFileError("--set " + path, "", "'" + (walked.empty() ? "the file" : walked) + "' is not an object");
        }
        walked += (walked.empty() ? "" : ".") + key;
        if (end != std::string::npos && !node->contains(key)) {
          (*node)[key] = path[end] == '[' ? json::array() : json::object();
        }
        node = &(*node)[key];
        i = end == std::string::npos ? path.size() : end;
      }
    }
    *node = value;
  }
}

SceneDescription readSceneJson(const json& document, const std::string& file) {
  SceneDescription scene;
  scene.file = file;
  const JsonFields fields(document, "", "scene");
  scene.description = fields.string("description", "");
  scene.gravity = fields.vec3("gravity", scene.gravity);
  scene.timeStep = fields.number("timeStep", scene.timeStep);
  if (fields.has("timeStep")) requirePositiveKey(fields, "timeStep", scene.timeStep);
  scene.duration = fields.number("duration", scene.duration);
  if (fields.has("duration")) requirePositiveKey(fields, "duration", scene.duration);
  if (fields.has("camera")) {
    const JsonFields camera(fields.at("camera"), "camera", "camera");
    scene.camera = readCamera(camera);
    scene.cameraFollow = camera.string("follow", "");
  }

  const std::string directory = file.empty() ? std::string() : std::filesystem::path(file).parent_path().string();
  Names names;
  for (const auto& [item, path] : fields.array("bodies")) {
    const JsonFields body(*item, path, "body");
    requireUniqueName(names.bodies, body, "body");
    scene.bodies.push_back(readBody(body, directory));
    for (const std::string& imported : scene.bodies.back().importedBodies) {
      names.bodies.insert(scene.bodies.back().name + "/" + imported);
    }
  }
  for (const auto& [item, path] : fields.array("ropes")) {
    const JsonFields rope(*item, path, "rope");
    requireUniqueName(names.ropes, rope, "rope");
    scene.ropes.push_back(readRope(rope));
    for (const AttachmentDescription& attachment : scene.ropes.back().attachments) {
      if (names.bodies.count(attachment.body) == 0) {
        throw SceneFileError(attachment.path + ".body", "\"" + attachment.body + "\"", "no body of that name");
      }
    }
  }
  if (!scene.cameraFollow.empty() && names.ropes.count(scene.cameraFollow) == 0) {
    throw SceneFileError("camera.follow", "\"" + scene.cameraFollow + "\"", "no rope of that name");
  }
  for (const auto& [item, path] : fields.array("events")) {
    scene.events.push_back(readEvent(JsonFields(*item, path, "event"), names));
  }
  std::set<std::string> checkNames;
  for (const auto& [item, path] : fields.array("checks")) {
    scene.checks.push_back(readCheck(JsonFields(*item, path, "check"), names, checkNames));
  }
  return scene;
}

SceneDescription readSceneText(const std::string& text, const std::string& file,
                               const std::vector<SceneOverride>& overrides) {
  json document;
  try {
    document = json::parse(text);
  } catch (const json::parse_error& error) {
    // nlohmann's message names the byte; strip its "[json.exception.parse_error.101] " prefix.
    std::string what = error.what();
    const std::size_t bracket = what.find("] ");
    if (bracket != std::string::npos) what = what.substr(bracket + 2);
    throw SceneFileError("", "", "not valid JSON: " + what);
  }
  applySceneOverrides(document, overrides);
  return readSceneJson(document, file);
}

SceneDescription readSceneFile(const std::string& file, const std::vector<SceneOverride>& overrides) {
  std::ifstream stream(file, std::ios::binary);
  if (!stream) throw SceneFileError("", "", "cannot open '" + file + "'");
  std::ostringstream text;
  text << stream.rdbuf();
  return readSceneText(text.str(), file, overrides);
}

}  // namespace rope::demos
