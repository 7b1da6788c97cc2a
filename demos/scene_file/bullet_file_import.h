// SPDX-License-Identifier: MIT
#pragma once
// The rigid bodies of a .bullet file (written by Bullet's btDefaultSerializer, e.g. from
// btDiscreteDynamicsWorld::serialize) in a scene file's world: `"shape": "bulletFile"`. Loaded with
// btBulletWorldImporter (Debian: libbullet-extras-dev), which adds them (and their constraints) to
// the world; they leave it again when this object goes. The file's gravity and solver settings are
// not taken: the scene file's apply.

#include <BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

class btBulletWorldImporter;

namespace rope::demos {

class BulletFileImport {
 public:
  // Throws std::runtime_error: "not found", "not a .bullet file ..." or "has no rigid bodies". The
  // world's gravity is restored after the import.
  BulletFileImport(btDiscreteDynamicsWorld& world, const std::string& file);
  ~BulletFileImport();
  BulletFileImport(const BulletFileImport&) = delete;
  BulletFileImport& operator=(const BulletFileImport&) = delete;

  // Every rigid body with its name in the file (the serializer's registered name), or "body<i>"
  // for an unnamed one (i: its index among the file's rigid bodies), in the file's order.
  const std::vector<std::pair<std::string, btRigidBody*>>& bodies() const { return bodies_; }

 private:
  // Takes what the importer created out of the world and deletes it (also after a failed load).
  void release();
  btDiscreteDynamicsWorld& world_;
  std::unique_ptr<btBulletWorldImporter> importer_;
  std::vector<std::pair<std::string, btRigidBody*>> bodies_;
};

}  // namespace rope::demos
