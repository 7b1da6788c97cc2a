#pragma once
// Ropes in a user's Bullet world. A RopeWorld wraps one btDiscreteDynamicsWorld (or a subclass such
// as btSoftRigidDynamicsWorld) and installs one btActionInterface in it, so every rope steps once per
// Bullet internal substep with Bullet's fixed step, right after that substep's collision detection,
// constraint solve and integration (stepSimulation(dt, maxSubSteps, fixedStep) works unchanged).
// In each substep it reads Bullet's pair cache for bodies overlapping the ropes' swept capsule boxes
// (re-checking the overlap: the cache keeps stale pairs for several steps), runs the bridge's
// narrowphase, applies the contact and attachment response (contact_response.h, attachment.h), steps
// the rods and refreshes the capsule boxes for the next substep.
//
// Ownership: the user owns the Bullet world, the bodies, the RopeWorld and the RopeObjects. The
// RopeWorld must be destroyed before the Bullet world (it removes its action and the ropes' capsules).

#include <BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h>

#include <functional>
#include <memory>
#include <vector>

#include "bullet_bridge/bullet_precision.h"
#include "bullet_bridge/contact_report.h"
#include "bullet_bridge/rope_object.h"
#include "bullet_bridge/rope_rope_contact.h"

namespace rope::bullet {

class RopeWorld {
 public:
  explicit RopeWorld(btDiscreteDynamicsWorld& world);
  ~RopeWorld();
  RopeWorld(const RopeWorld&) = delete;
  RopeWorld& operator=(const RopeWorld&) = delete;

  // Registers the rope's capsules in the broadphase (settings().collisionGroup / collisionMask).
  // Throws InvalidArgument("rope", ...) if the rope is already in this or another world.
  void addRope(RopeObject& rope);
  // Takes the rope's capsules out again; its attachments stay defined but act only in a world.
  // Throws InvalidArgument("rope", ...) if the rope is not in this world.
  void removeRope(RopeObject& rope);
  bool contains(const RopeObject& rope) const;
  const std::vector<RopeObject*>& ropes() const { return ropes_; }

  btDiscreteDynamicsWorld& dynamicsWorld() { return world_; }
  const btDiscreteDynamicsWorld& dynamicsWorld() const { return world_; }
  // True if the object is one of the Bullet world's collision objects (and not a rope capsule).
  bool containsBody(const btCollisionObject& object) const;

  // The contacts and rope states of the last substep; the callback (if set) sees every substep.
  const ContactReport& lastReport() const { return report_; }
  void setSubstepCallback(std::function<void(const ContactReport&)> callback) { callback_ = std::move(callback); }

  // Whether btDiscreteDynamicsWorld::debugDrawWorld also draws the ropes (rope_debug_draw.h). Default on.
  void setDebugDrawEnabled(bool enabled) { debugDraw_ = enabled; }
  bool debugDrawEnabled() const { return debugDraw_; }

 private:
  class Action;
  void substep(double h);

  btDiscreteDynamicsWorld& world_;
  std::unique_ptr<Action> action_;
  std::vector<RopeObject*> ropes_;
  std::vector<std::vector<const btCollisionObject*>> candidates_;  // per rope, scratch
  std::vector<RopeCapsulePair> capsulePairs_;                       // scratch
  std::vector<RopeCapsulePair> sortedPairs_;                        // scratch of sortCapsulePairs
  std::vector<int> pairBuckets_, ropeOffsets_, bucketFill_;        // scratch of sortCapsulePairs
  // Puts capsulePairs_ in (ropeA, capsuleA, ropeB, capsuleB) order in O(pairs + capsules).
  void sortCapsulePairs();
  RopeRopeContacts ropeRopeContacts_;
  ContactReport report_;
  std::function<void(const ContactReport&)> callback_;
  bool debugDraw_ = true;
};

}  // namespace rope::bullet
