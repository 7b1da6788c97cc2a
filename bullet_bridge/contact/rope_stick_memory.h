// SPDX-License-Identifier: MIT
#pragma once
// The stick state of distributed rope-rope contact, carried from one substep to the next along the
// sampled rope (rope_rope_contact.h).
//
// A sample of a distributed rope-rope contact that sticks is held by a tangential spring whose stretch
// e (m, world frame, in the contact's tangent plane) grows with the relative slip of the two ropes at
// the sample, e_new = e + h P_t w_new (docs/method.md §12). Samples are Gauss nodes of capsule pieces,
// which move in the parameter whenever knots are inserted or removed, but the curve parameter s itself
// is material (insertion and removal keep the parametrisation), so the stretches are stored as a field
// along s of the sampled rope, per pair of ropes: a new sample at s takes the stretch interpolated
// linearly between the stored ones on either side of s, or the one nearest if only one side has one.
// A sliding sample stores the stretch that puts its spring at the friction force it ended the step
// with, and a flag, so that it starts the next substep sliding, or sticks again still carrying its load.
//
// Ropes are named by address: a rope that leaves the world or is cut must be forgotten first.
// Not API: installed only because rope_rope_contact.h includes it; may change in any release.

#include <vector>

#include "rope/common/types.h"

namespace rope::bullet {

class RopeObject;

class RopeStickMemory {
 public:
  // The stretch for a sample at parameter s of `sampled` touching `other`, from the stored entries
  // within `reach` (parameter units) of s. Returns false (leaving the outputs alone) if there is none.
  bool find(const RopeObject& sampled, const RopeObject& other, double s, double reach, Vec3& stretch,
            bool& sliding) const;
  // Builds the next substep's store: add() in any order, then commit() replaces the stored entries
  // (find() reads the old ones until then).
  void add(const RopeObject& sampled, const RopeObject& other, double s, const Vec3& stretch, bool sliding);
  void commit();
  // Drops every entry naming the rope (either side), or all of them.
  void forget(const RopeObject& rope);
  void clear();
  int size() const { return static_cast<int>(entries_.size()); }

 private:
  struct Entry {
    const RopeObject* sampled = nullptr;
    const RopeObject* other = nullptr;
    double s = 0.0;
    Vec3 stretch = Vec3::Zero();  // m
    bool sliding = false;
  };
  static bool before(const Entry& a, const Entry& b);
  std::vector<Entry> entries_;  // sorted by (sampled, other, s)
  std::vector<Entry> next_;
};

}  // namespace rope::bullet
