// SPDX-License-Identifier: MIT
#include "reliability/reliability_support.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include <sys/mman.h>
#include <unistd.h>

namespace rope::test {

class ActionWorld::World : public btDiscreteDynamicsWorld {
 public:
  using btDiscreteDynamicsWorld::btDiscreteDynamicsWorld;
  using btDiscreteDynamicsWorld::updateActions;
  int actionCount() const { return m_actions.size(); }
};

namespace {

// Small pools: Bullet's defaults (4096 manifolds and collision algorithms) allocate and clear
// megabytes per world, which dominated the fuzzers' short scenes; an exhausted pool falls back to
// the heap, so only the allocation pattern differs.
btDefaultCollisionConstructionInfo smallPools() {
  btDefaultCollisionConstructionInfo info;
  info.m_defaultMaxPersistentManifoldPoolSize = 64;
  info.m_defaultMaxCollisionAlgorithmPoolSize = 64;
  return info;
}

}  // namespace

ActionWorld::ActionWorld(const btVector3& gravity)
    : configuration_(std::make_unique<btDefaultCollisionConfiguration>(smallPools())),
      dispatcher_(std::make_unique<btCollisionDispatcher>(configuration_.get())),
      broadphase_(std::make_unique<btDbvtBroadphase>()),
      solver_(std::make_unique<btSequentialImpulseConstraintSolver>()),
      world_(std::make_unique<World>(dispatcher_.get(), broadphase_.get(), solver_.get(), configuration_.get())) {
  world_->setGravity(gravity);
}

ActionWorld::~ActionWorld() {
  for (btRigidBody* body : bodies_) {
    world_->removeRigidBody(body);
    delete body;
  }
}

btDiscreteDynamicsWorld& ActionWorld::world() { return *world_; }
const btDiscreteDynamicsWorld& ActionWorld::world() const { return *world_; }

void ActionWorld::runActions(btScalar dt) { world_->updateActions(dt); }

int ActionWorld::actionCount() const { return world_->actionCount(); }

btRigidBody* ActionWorld::addBox(const btVector3& halfExtents, double mass, const btVector3& origin) {
  shapes_.push_back(std::make_unique<btBoxShape>(halfExtents));
  btVector3 inertia(0, 0, 0);
  if (mass > 0) shapes_.back()->calculateLocalInertia(btScalar(mass), inertia);
  btRigidBody::btRigidBodyConstructionInfo info(btScalar(mass), nullptr, shapes_.back().get(), inertia);
  info.m_startWorldTransform.setOrigin(origin);
  auto* body = new btRigidBody(info);
  world_->addRigidBody(body);
  bodies_.push_back(body);
  return body;
}

btRigidBody* ActionWorld::addStatic(btCollisionShape& shape, const btVector3& origin) {
  btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, &shape);
  info.m_startWorldTransform.setOrigin(origin);
  auto* body = new btRigidBody(info);
  world_->addRigidBody(body);
  bodies_.push_back(body);
  return body;
}

void ActionWorld::deleteBody(btRigidBody* body) {
  world_->removeRigidBody(body);
  bodies_.erase(std::remove(bodies_.begin(), bodies_.end(), body), bodies_.end());
  delete body;
}

void ActionWorld::step(int substeps, double h) {
  for (int i = 0; i < substeps; ++i) world_->stepSimulation(btScalar(h), 1, btScalar(h));
}

void ThrowingGroundShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const {
  const btVector3 extent(half_, btScalar(0.01), half_);
  aabbMin = t.getOrigin() - extent;
  aabbMax = t.getOrigin() + extent;
}

void ThrowingGroundShape::processAllTriangles(btTriangleCallback* callback, const btVector3&,
                                              const btVector3&) const {
  if (armed_) throw std::runtime_error("injected narrowphase failure");
  btVector3 a(-half_, 0, -half_), b(half_, 0, -half_), c(half_, 0, half_), d(-half_, 0, half_);
  btVector3 first[3] = {a, c, b};  // counter-clockwise seen from above: normal +y
  btVector3 second[3] = {a, d, c};
  callback->processTriangle(first, 0, 0);
  callback->processTriangle(second, 0, 1);
}

namespace {
std::size_t pageRounded(std::size_t bytes) {
  const std::size_t page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  return (bytes + page - 1) / page * page;
}
}  // namespace

void* allocatePages(std::size_t bytes) {
  void* memory = mmap(nullptr, pageRounded(bytes), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (memory == MAP_FAILED) throw std::bad_alloc();
  return memory;
}

void protectPages(void* memory, std::size_t bytes) {
  if (mprotect(memory, pageRounded(bytes), PROT_NONE) != 0) throw std::runtime_error("mprotect failed");
}

void releasePages(void* memory, std::size_t bytes) { munmap(memory, pageRounded(bytes)); }

std::vector<double> rodState(const Rod& rod) {
  std::vector<double> state;
  for (int i = 0; i < rod.knots().size(); ++i) state.push_back(rod.knots()[i]);
  for (const PointList* list : {&rod.controlPoints(), &rod.velocities(), &rod.restControlPoints()}) {
    for (const Vec3& p : *list) state.insert(state.end(), {p.x(), p.y(), p.z()});
  }
  for (const Pin& pin : rod.pins()) {
    state.insert(state.end(), {static_cast<double>(pin.id), pin.parameter, pin.target.x(), pin.target.y(), pin.target.z()});
  }
  return state;
}

bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

}  // namespace rope::test
