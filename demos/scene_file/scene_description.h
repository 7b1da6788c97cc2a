// SPDX-License-Identifier: MIT
#pragma once
// A scene file in memory: what `ropesim run FILE.json` reads (scene_file_reader.h) and FileScene
// (file_scene.h) builds. Plain data, SI units; docs/scene-files.md lists every key with its unit,
// default and range, and docs/scene-file.schema.json is the same list as a JSON Schema.
//
// The scene-file module lives in demos/ next to the built-in scene builders (demos/scenes), which it
// reuses (PhysicsWorld, the pile's coil, the knot region): it is a front end of ropesim, not part of
// the installed libraries, so the library gains no JSON dependency.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "bullet_bridge/attachment.h"
#include "bullet_bridge/rope_settings.h"
#include "bullet_bridge/winch.h"
#include "render/camera.h"
#include "rope/common/types.h"
#include "rope/rod/rod.h"
#include "rope/rod/rod_settings.h"

namespace rope::demos {

// A pose at a time, for kinematic bodies and moving pins; interpolated between keyframes (positions
// linearly, rotations by slerp, in the fraction u of the interval or in smoothstep(u)), held before the
// first and after the last.
struct Keyframe {
  enum class Interpolation { kLinear, kSmoothstep };
  double time = 0.0;                            // s
  Vec3 position = Vec3::Zero();                 // m, world frame
  Eigen::Vector4d rotation{0.0, 0.0, 0.0, 1.0}; // unit quaternion (x, y, z, w), as btQuaternion
  // From this keyframe to the next: u itself, or u^2 (3 - 2u), which starts and stops at rest.
  Interpolation interpolation = Interpolation::kLinear;
};

struct BodyDescription {
  enum class Shape { kBox, kSphere, kCapsule, kCylinder, kPlane, kMesh, kBulletFile };
  enum class MeshType { kConvexHull, kTriangleMesh };
  enum class Motion { kStatic, kKinematic, kDynamic };
  std::string name;
  Shape shape = Shape::kBox;
  Motion motion = Motion::kStatic;
  Vec3 halfExtents = Vec3::Zero();  // box, cylinder (the component along `axis` is the cylinder's half length), m
  double radius = 0.0;              // sphere, capsule, m
  double height = 0.0;              // capsule: distance between the two hemisphere centres (along its axis), m
  int axis = 1;                     // cylinder, capsule: their axis in the body frame, 0 x, 1 y, 2 z
  Vec3 normal{0.0, 1.0, 0.0};       // plane: unit normal
  double offset = 0.0;              // plane: n . x = offset, m
  std::string mesh;                 // mesh: the OBJ file as the scene file names it
  MeshType meshType = MeshType::kConvexHull;  // mesh: btConvexHullShape, or btBvhTriangleMeshShape (static)
  double scale = 1.0;               // mesh: factor applied to the OBJ's coordinates
  double margin = 0.0;              // convex hull: Bullet's collision margin around it, m
  PointList meshVertices;           // mesh: read with the file (so a bad mesh stops before simulating), m
  std::vector<std::array<int, 3>> meshTriangles;
  std::string file;                      // bulletFile: the .bullet file, resolved against the scene file's directory
  std::vector<std::string> importedBodies;  // bulletFile: its bodies' names; the scene calls them "<name>/<body>"
  double mass = 0.0;                // dynamic: kg, > 0
  Vec3 position = Vec3::Zero();     // m
  Eigen::Vector4d rotation{0.0, 0.0, 0.0, 1.0};  // unit quaternion (x, y, z, w)
  Vec3 linearVelocity = Vec3::Zero();            // m/s (dynamic)
  Vec3 angularVelocity = Vec3::Zero();           // rad/s (dynamic)
  double friction = 0.5;            // Bullet's body coefficient (combined with the rope's), >= 0
  double restitution = 0.0;         // >= 0
  bool canSleep = false;            // dynamic: Bullet may deactivate it when it comes to rest
  std::optional<Vec3> gravity;      // dynamic: its own gravity instead of the world's, m/s^2
  double gravityRampTime = 0.0;     // s: its own gravity grows linearly from zero over this time
  std::vector<Keyframe> keyframes;  // kinematic bodies: the scripted pose over time
};

struct RopeShapeDescription {
  enum class Kind { kSegment, kPolyline, kHelix, kCoil };
  Kind kind = Kind::kSegment;
  Vec3 from = Vec3::Zero(), to = Vec3::Zero();  // segment, m
  PointList points;                             // polyline, m
  Rod::RestShape restShape = Rod::RestShape::kScaledToRestLength;  // polyline, helix
  Vec3 center = Vec3::Zero();  // helix: centre of its first point's circle; coil: (x, lowest height, z)
  double radius = 0.0;         // helix, coil: m
  double pitch = 0.0;          // helix, coil: rise per turn, m
  double turns = 0.0;          // helix: number of turns
  int pointsPerTurn = 16;      // helix
  double tilt = 0.0;           // coil: lean of the axis from the vertical about x, rad
};

// A rope parameter in a file: a number (m of the rope's parameter, 0 at its beginning) or one of the
// words "begin" / "end".
struct RopeParameter {
  enum class Kind { kValue, kBegin, kEnd };
  Kind kind = Kind::kValue;
  double value = 0.0;
};

struct PinDescription {
  std::string path;                  // "ropes[0].pins[1]", for messages
  std::string name;                  // optional; checks name it
  RopeParameter s;
  std::optional<Vec3> target;        // default: where the rope is at s
  std::vector<Keyframe> keyframes;   // a moving target (positions only)
};

struct AttachmentDescription {
  std::string path;  // "ropes[0].clamps[1]", for messages
  std::string name;  // optional; checks name it
  RopeParameter s;
  std::string body;
  Vec3 localPoint = Vec3::Zero();
  bool clamp = false;
  Vec3 localDirection{1.0, 0.0, 0.0};  // clamps
  bullet::AttachmentSettings settings;
};

struct WinchDescription {
  std::string path;
  bullet::RopeEnd end = bullet::RopeEnd::kEnd;
  double speed = 0.0;                 // m/s of rest length (> 0 pays out)
  std::optional<double> restLength;   // winchTo: stop at this rest length, m
  double start = 0.0;                 // s: when it starts
};

struct RopeDescription {
  std::string name;
  RodSettings rod;
  bullet::BulletRopeSettings bridge;
  RopeShapeDescription shape;
  std::vector<PinDescription> pins;
  std::vector<AttachmentDescription> attachments;  // attachments and clamps, in file order
  std::vector<WinchDescription> winches;
  bool showControlPolygon = false;
};

// Something that happens at a time (forces: over [time, until)).
struct EventDescription {
  enum class Kind { kCut, kRopeForce, kRopeDistributedForce, kBodyForce, kBodyVelocity, kRelease };
  Kind kind = Kind::kCut;
  std::string path;  // where it is in the file, for messages
  double time = 0.0;
  double until = 0.0;  // forces: end of the interval, s (> time)
  std::string rope, body, attachment;
  RopeParameter s;
  RopeParameter s0{RopeParameter::Kind::kBegin, 0.0};  // distributed force: over [s0, s1] of the rope
  RopeParameter s1{RopeParameter::Kind::kEnd, 0.0};
  Vec3 vector = Vec3::Zero();  // force (N), force per length (N/m of rest length) or linear velocity (m/s)
  Vec3 angular = Vec3::Zero(); // body velocity: angular velocity, rad/s
  std::string newName;         // cut: the name of the piece beyond s
};

struct CheckDescription {
  enum class Kind { kPenetration, kContact, kTension, kPosition, kSlip, kHealth, kKnotLength };
  Kind kind = Kind::kPenetration;
  std::string name;
  std::string path;        // where it is in the file, for messages
  double from = 0.0;       // window, s
  double to = 1e300;
  std::optional<double> at;  // position checks: one time instead of the window
  std::string rope, body, attachment;
  std::optional<RopeParameter> s;           // tension at s, position of a rope point
  std::optional<bullet::RopeEnd> winch;     // tension at a winch
  bool never = false;                       // contact: never touches (false: stays in contact)
  std::optional<double> min, max;           // bounds of the measured value
  std::optional<Vec3> boxMin, boxMax;       // position: inside this box
  std::optional<Vec3> target;               // position: within max of this point
  Vec3 localPoint = Vec3::Zero();           // slip, position of a body: the body's point
};

struct SceneDescription {
  std::string file;              // path it was read from ("" for a string)
  std::string description;
  Vec3 gravity{0.0, -9.81, 0.0}; // m/s^2
  double timeStep = 1.0 / 240.0; // s
  double duration = 5.0;         // s simulated by default
  std::vector<BodyDescription> bodies;
  std::vector<RopeDescription> ropes;
  std::vector<EventDescription> events;
  std::vector<CheckDescription> checks;
  std::optional<render::Camera> camera;  // nullopt: framed automatically on the first frame
  std::string cameraFollow;  // a rope's name: the camera keeps its offset to that rope's mean point
};

}  // namespace rope::demos
