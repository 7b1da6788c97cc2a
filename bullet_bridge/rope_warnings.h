// SPDX-License-Identifier: MIT
#pragma once
// Warning counters of the ropes in a Bullet world. Code that runs inside btDiscreteDynamicsWorld::
// stepSimulation never throws through the user's loop: whatever goes wrong in a rope's substep (a
// failed solve, a non-finite body, an exception from the rope's own code or from a user callback) is
// caught, the rope keeps its last good state, the substep's report says why (RopeStepRecord::failure,
// KinematicRopeStepReport::failure) and a counter below goes up, as MuJoCo counts its mjWARN_*
// warnings instead of stopping. The counters only grow (since the object was created); compare two
// readings to see what one step did.

namespace rope::bullet {

// One dynamic rope (RopeObject::warnings()).
struct RopeWarnings {
  long failedSteps = 0;          // substeps whose rod step failed or was skipped (the rope kept its state)
  long exceptions = 0;           // of those: an exception was caught in the rope's substep (RopeObject::lastError())
  long skippedBodies = 0;        // candidate or attached bodies passed over: non-finite state, unsupported shape
  long droppedAttachments = 0;   // body attachments dropped because their body left the Bullet world
  int consecutiveFailures = 0;   // failed substeps since the last successful one (0: the last one succeeded)
  long timesPutToRest = 0;       // times the rope was put to rest (RopeObject::kFailuresBeforeRest failures in a row)
  long restingSubsteps = 0;      // substeps spent at rest (frozen, still colliding; not counted in failedSteps)
  // Substeps whose contact active set had not settled at its last pass (RopeStepRecord::
  // contactsUnsettled): a quality warning, not a failure, so not in total().
  long unsettledContactSteps = 0;
  long total() const { return failedSteps + skippedBodies + droppedAttachments + timesPutToRest; }
};

// A RopeWorld as a whole (RopeWorld::warnings()).
struct RopeWorldWarnings {
  long skippedSubsteps = 0;      // substeps with a time step that is not finite and > 0: no rope stepped
  long ropeContactFailures = 0;  // rope-rope contact solves that failed or threw (contacts skipped that substep)
  long callbackExceptions = 0;   // exceptions thrown by the substep callback (caught; RopeWorld::lastError())
  long exceptions = 0;           // other exceptions caught in the world's substep (RopeWorld::lastError())
  long total() const { return skippedSubsteps + ropeContactFailures + callbackExceptions + exceptions; }
};

// One kinematic rope (KinematicRope::warnings()).
struct KinematicRopeWarnings {
  long skippedSubsteps = 0;      // substeps with a time step that is not finite and > 0: the rope did not move
  long targetFailures = 0;       // substeps whose driver gave no usable target (the leading end held)
  long pathExceptions = 0;       // of those: the followPath function threw (caught; KinematicRope::lastError())
  long exceptions = 0;           // other exceptions caught in the rope's substep (KinematicRope::lastError())
  long unsupportedBodies = 0;    // bodies passed through: shape the narrowphase does not support, non-finite state
  long total() const { return skippedSubsteps + targetFailures + exceptions + unsupportedBodies; }
};

}  // namespace rope::bullet
