// SPDX-License-Identifier: MIT
#pragma once
// The peer of RestingRopeScene (surface kBox) in Bullet's own soft bodies: straight ropes made by
// btSoftBodyHelpers::CreateRope (as demos/compare does), lying side by side on the same static box in
// a btSoftRigidDynamicsWorld, so that benchmarks can time both kinds of rope on the same scene in
// one program. Length, mass (lumped at the nodes from the linear density), collision radius (the soft
// body's margin), friction and gravity match the SplineRope side; the soft rope's links are
// position-based constraints (kLST = 1, piterations solver passes) with no bending stiffness.

#include <btBulletDynamicsCommon.h>

#include <memory>
#include <vector>

class btSoftBody;
class btSoftRigidDynamicsWorld;
class btSoftBodyRigidBodyCollisionConfiguration;

namespace rope::demos {

struct SoftBodyRopesSceneSettings {
  int ropeCount = 1;            // >= 1
  double ropeLength = 1.0;      // m, > 0
  double spacing = 0.05;        // m, > 2 radius: distance between neighbouring ropes (along z)
  double radius = 0.005;        // m, > 0: the soft body's collision margin (RodSettings{}.radius)
  double linearDensity = 0.0903207887907066;  // kg/m, > 0: RodSettings{}'s 1150 kg/m^3 * pi (5 mm)^2
  int segments = 16;            // links per rope, >= 2 (CreateRope makes segments + 1 nodes)
  int iterations = 4;           // btSoftBody::m_cfg.piterations, >= 1
  double friction = 0.5;        // m_cfg.kDF, in [0, 1] (the box's friction is 0.5 too)
  double timeStep = 1.0 / 240.0;  // s, > 0
};

class SoftBodyRopesScene {
 public:
  // Throws InvalidArgument naming the field for bad settings.
  explicit SoftBodyRopesScene(const SoftBodyRopesSceneSettings& settings);
  ~SoftBodyRopesScene();
  SoftBodyRopesScene(const SoftBodyRopesScene&) = delete;
  SoftBodyRopesScene& operator=(const SoftBodyRopesScene&) = delete;

  // One stepSimulation of timeStep (one substep).
  void step();
  double timeStep() const { return settings_.timeStep; }
  int ropeCount() const { return static_cast<int>(ropes_.size()); }
  const btSoftBody& rope(int i) const { return *ropes_.at(static_cast<std::size_t>(i)); }
  // Lowest node of all ropes (m) and largest node speed (m/s).
  double lowestNode() const;
  double maxSpeed() const;

 private:
  SoftBodyRopesSceneSettings settings_;
  std::unique_ptr<btSoftBodyRigidBodyCollisionConfiguration> configuration_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btDbvtBroadphase> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<btSoftRigidDynamicsWorld> world_;
  std::unique_ptr<btBoxShape> boxShape_;
  std::unique_ptr<btRigidBody> box_;
  std::vector<std::unique_ptr<btSoftBody>> ropes_;
};

}  // namespace rope::demos
