// SPDX-License-Identifier: MIT
#include "demos/scene_file/bullet_file_import.h"

#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <BulletWorldImporter/btBulletWorldImporter.h>

#include <fstream>
#include <set>
#include <stdexcept>

namespace rope::demos {

BulletFileImport::BulletFileImport(btDiscreteDynamicsWorld& world, const std::string& file) : world_(world) {
  if (!std::ifstream(file)) throw std::runtime_error("not found");
  // Bullet's files start with "BULLET" (then the pointer size, the endianness and the version);
  // the importer is not asked to parse anything else.
  char magic[7] = {};
  std::ifstream(file, std::ios::binary).read(magic, 6);
  if (std::string(magic) != "BULLET") throw std::runtime_error("not a .bullet file (no BULLET header)");
  const btVector3 gravity = world.getGravity();
  importer_ = std::make_unique<btBulletWorldImporter>(&world);
  const bool loaded = importer_->loadFile(file.c_str());
  world.setGravity(gravity);
  if (!loaded) {
    release();
    throw std::runtime_error("not a .bullet file btBulletWorldImporter can read");
  }
  std::set<std::string> names;
  for (int i = 0; i < importer_->getNumRigidBodies(); ++i) {
    btRigidBody* body = btRigidBody::upcast(importer_->getRigidBodyByIndex(i));
    if (body == nullptr) continue;
    const char* name = importer_->getNameForPointer(body);
    std::string chosen = name != nullptr && *name != '\0' ? name : "body" + std::to_string(i);
    // Two bodies of one name: the later ones get their index (names must be unique in a scene file).
    if (!names.insert(chosen).second) chosen += "#" + std::to_string(i);
    names.insert(chosen);
    bodies_.emplace_back(chosen, body);
  }
  if (bodies_.empty()) {
    release();
    throw std::runtime_error("has no rigid bodies");
  }
}

BulletFileImport::~BulletFileImport() { release(); }

void BulletFileImport::release() {
  if (!importer_) return;
  for (int i = 0; i < importer_->getNumConstraints(); ++i) world_.removeConstraint(importer_->getConstraintByIndex(i));
  for (int i = 0; i < importer_->getNumRigidBodies(); ++i) world_.removeCollisionObject(importer_->getRigidBodyByIndex(i));
  importer_->deleteAllData();
  importer_.reset();
}

}  // namespace rope::demos
