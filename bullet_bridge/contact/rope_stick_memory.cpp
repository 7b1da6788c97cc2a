// SPDX-License-Identifier: MIT
#include "bullet_bridge/contact/rope_stick_memory.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace rope::bullet {

bool RopeStickMemory::before(const Entry& a, const Entry& b) {
  // std::less gives pointers a total order; the order only has to be the same within one run.
  const std::less<const RopeObject*> less;
  if (a.sampled != b.sampled) return less(a.sampled, b.sampled);
  if (a.other != b.other) return less(a.other, b.other);
  return a.s < b.s;
}

bool RopeStickMemory::find(const RopeObject& sampled, const RopeObject& other, double s, double reach, Vec3& stretch,
                           bool& sliding) const {
  Entry key;
  key.sampled = &sampled;
  key.other = &other;
  key.s = s;
  const auto after = std::lower_bound(entries_.begin(), entries_.end(), key, before);
  const auto same = [&](const Entry& e) { return e.sampled == &sampled && e.other == &other && std::abs(e.s - s) <= reach; };
  const Entry* right = after != entries_.end() && same(*after) ? &*after : nullptr;
  const Entry* left = after != entries_.begin() && same(*(after - 1)) ? &*(after - 1) : nullptr;
  if (left == nullptr && right == nullptr) return false;
  if (left != nullptr && right != nullptr && right->s > left->s) {
    const double t = (s - left->s) / (right->s - left->s);
    stretch = (1.0 - t) * left->stretch + t * right->stretch;
    sliding = t < 0.5 ? left->sliding : right->sliding;
    return true;
  }
  const Entry& nearest = left != nullptr ? *left : *right;
  stretch = nearest.stretch;
  sliding = nearest.sliding;
  return true;
}

void RopeStickMemory::add(const RopeObject& sampled, const RopeObject& other, double s, const Vec3& stretch,
                          bool sliding) {
  Entry entry;
  entry.sampled = &sampled;
  entry.other = &other;
  entry.s = s;
  entry.stretch = stretch;
  entry.sliding = sliding;
  next_.push_back(entry);
}

void RopeStickMemory::commit() {
  std::sort(next_.begin(), next_.end(), before);
  entries_.swap(next_);
  next_.clear();
}

void RopeStickMemory::forget(const RopeObject& rope) {
  const auto names = [&](const Entry& e) { return e.sampled == &rope || e.other == &rope; };
  entries_.erase(std::remove_if(entries_.begin(), entries_.end(), names), entries_.end());
  next_.erase(std::remove_if(next_.begin(), next_.end(), names), next_.end());
}

void RopeStickMemory::clear() {
  entries_.clear();
  next_.clear();
}

}  // namespace rope::bullet
