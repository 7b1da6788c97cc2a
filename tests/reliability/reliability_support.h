// SPDX-License-Identifier: MIT
#pragma once
// Shared pieces of the reliability tests (tests/reliability/): a Bullet world whose actions a test
// can run directly (to hand the ropes a bad time step with the floating-point traps still on), and
// a concave shape that throws from its triangle callback when armed (to inject an exception into a
// rope's narrowphase, the way a user's own shape class could).

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionShapes/btConcaveShape.h>

#include <cstddef>
#include <memory>
#include <new>
#include <utility>
#include <stdexcept>
#include <vector>

#include "rope/rod/rod.h"

namespace rope::test {

// A stock dynamics world (default configuration, dbvt broadphase, sequential-impulse solver) that
// exposes btDiscreteDynamicsWorld::updateActions, the call stepSimulation makes once per substep.
class ActionWorld {
 public:
  explicit ActionWorld(const btVector3& gravity = btVector3(0, btScalar(-9.81), 0));
  ~ActionWorld();  // removes and deletes the bodies it made (not the user's)

  btDiscreteDynamicsWorld& world();
  const btDiscreteDynamicsWorld& world() const;
  // What stepSimulation does to the actions in one substep of dt (no collision detection, no bodies).
  void runActions(btScalar dt);
  // How many actions (btActionInterface) the world holds.
  int actionCount() const;
  // A box of the given half extents; mass 0 makes it static.
  btRigidBody* addBox(const btVector3& halfExtents, double mass, const btVector3& origin);
  // A static body with the caller's shape (not owned), at origin.
  btRigidBody* addStatic(btCollisionShape& shape, const btVector3& origin);
  // Takes a body made by addBox out of the world and deletes it (as a user would).
  void deleteBody(btRigidBody* body);
  void step(int substeps, double h = 1.0 / 240.0);

 private:
  class World;
  std::unique_ptr<btDefaultCollisionConfiguration> configuration_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btDbvtBroadphase> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<World> world_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<btRigidBody*> bodies_;
};

// A flat square of two triangles in the plane y = 0 (half size `half`, m), whose processAllTriangles
// throws std::runtime_error("injected narrowphase failure") while armed. It calls itself a terrain
// (CUSTOM_CONCAVE_SHAPE_TYPE is Bullet's SDF type, which the narrowphase refuses): any concave type
// reaches the rope's triangle narrowphase through processAllTriangles.
class ThrowingGroundShape : public btConcaveShape {
 public:
  explicit ThrowingGroundShape(btScalar half) : half_(half) { m_shapeType = TERRAIN_SHAPE_PROXYTYPE; }
  void arm(bool armed) { armed_ = armed; }
  void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;
  void processAllTriangles(btTriangleCallback* callback, const btVector3& aabbMin, const btVector3& aabbMax) const override;
  void setLocalScaling(const btVector3& scaling) override { scaling_ = scaling; }
  const btVector3& getLocalScaling() const override { return scaling_; }
  void calculateLocalInertia(btScalar, btVector3& inertia) const override { inertia.setZero(); }
  const char* getName() const override { return "ThrowingGround"; }

 private:
  btScalar half_;
  bool armed_ = false;
  btVector3 scaling_{1, 1, 1};
};

// Page-granular memory for Guarded below (mmap, mprotect, munmap).
void* allocatePages(std::size_t bytes);
void protectPages(void* memory, std::size_t bytes);
void releasePages(void* memory, std::size_t bytes);

// Memory that faults on any access after its object is destroyed, like Electric Fence: the object
// lives alone in its own pages, and destroy() runs its destructor and then revokes all access to the
// pages (they stay reserved, so no later allocation can reuse the address). A use after free then
// stops the test with SIGSEGV in every build, not only under AddressSanitizer.
template <class T>
class Guarded {
 public:
  template <class... Args>
  explicit Guarded(Args&&... args) : memory_(allocatePages(sizeof(T))) {
    object_ = new (memory_) T(std::forward<Args>(args)...);
  }
  ~Guarded() {
    if (object_ != nullptr) object_->~T();
    releasePages(memory_, sizeof(T));
  }
  Guarded(const Guarded&) = delete;
  Guarded& operator=(const Guarded&) = delete;
  T* get() const { return object_; }
  T& operator*() const { return *object_; }
  T* operator->() const { return object_; }
  // Destroys the object and makes its memory inaccessible.
  void destroy() {
    object_->~T();
    object_ = nullptr;
    protectPages(memory_, sizeof(T));
  }

 private:
  void* memory_;
  T* object_ = nullptr;
};

// Every number of a rod's state, bit for bit (knots, control points, velocities, rest curve, pins):
// "unchanged" in these tests means equal snapshots.
std::vector<double> rodState(const Rod& rod);
// Same length and the same bits (so -0 differs from +0, and a NaN equals the same NaN).
bool sameBits(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace rope::test
