// SPDX-License-Identifier: MIT
#pragma once
// Meshes of Bullet shapes built once and reused frame after frame. Entries are keyed by the shape's
// address and checked against a fingerprint (type, local scaling, margin, local bounds), so a shape
// that was resized, or freed with another allocated at the same address, is rebuilt rather than
// drawn stale. Shapes whose vertices are edited in place keep their fingerprint only if their
// bounds do not change: call clear() after such edits.

#include <array>
#include <memory>
#include <unordered_map>

#include "render/shape_mesh.h"

namespace rope::render {

class ShapeMeshCache {
 public:
  // Throws like buildShapeMesh for bad options.
  explicit ShapeMeshCache(const ShapeMeshOptions& options = {});

  // The mesh of shape in its local frame; built on first use (may throw like buildShapeMesh).
  std::shared_ptr<const Mesh> get(const btCollisionShape& shape);

  std::size_t size() const { return entries_.size(); }
  std::size_t buildCount() const { return builds_; }  // meshes built since construction
  void clear() { entries_.clear(); }
  const ShapeMeshOptions& options() const { return options_; }

 private:
  using Fingerprint = std::array<double, 11>;
  struct Entry {
    Fingerprint fingerprint;
    std::shared_ptr<const Mesh> mesh;
  };
  ShapeMeshOptions options_;
  std::unordered_map<const btCollisionShape*, Entry> entries_;
  std::size_t builds_ = 0;
};

}  // namespace rope::render
