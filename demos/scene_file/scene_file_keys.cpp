// SPDX-License-Identifier: MIT
#include "demos/scene_file/scene_file_keys.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace rope::demos {

const std::vector<SceneFileKeyTable>& sceneFileKeyTables() {
  static const std::vector<SceneFileKeyTable> tables = {
      {"scene", {"description", "gravity", "timeStep", "duration", "camera", "bodies", "ropes", "events", "checks"}},
      {"camera", {"eye", "target", "up", "verticalFovDegrees", "follow"}},
      {"body",
       {"name", "shape", "motion", "halfExtents", "radius", "height", "axis", "normal", "offset", "mesh", "meshType", "scale", "margin", "file",
        "mass", "position", "rotation", "linearVelocity", "angularVelocity", "friction", "restitution", "canSleep", "gravity",
        "gravityRampTime", "keyframes"}},
      {"keyframe", {"time", "position", "rotation", "interpolation"}},
      {"rope", {"name", "settings", "shape", "pins", "attachments", "clamps", "winches", "showControlPolygon"}},
      {"rope.settings",
       {// RodSettings (rope/rod/rod_settings.h)
        "restLength", "radius", "linearDensity", "materialDensity", "youngsModulus", "bendingStiffness",
        "massDamping", "stiffnessDamping", "materialDamping", "gravity", "timeIntegrator", "degree", "initialControlPoints", "stretchingQuadrature",
        "adaptive", "minControlPoints", "maxControlPoints", "insertAngle", "removeAngle", "removalErrorBound",
        "removalVelocityErrorBound", "removalCriterion", "removalRelativeError", "minKnotSpacing",
        // BulletRopeSettings (bullet_bridge/rope_settings.h)
        "lineContactStiffness", "lineContactDamping", "lineSpeculativeDamping", "contactQuadraturePoints",
        "concentratedContactRatio", "friction", "frictionVelocity", "gravitySource", "gravityScale", "fluidDensity",
        "normalDragCoefficient", "tangentialDragCoefficient", "windVelocity", "contactStiffness", "contactDamping",
        "speculativeDamping", "capsulesPerSpan", "speculativeMargin", "initialPredictionTime", "bodyStabilityFactor",
        "collisionGroup", "collisionMask", "selfContact", "selfContactExclusion"}},
      {"rope.shape", {"type", "from", "to", "points", "restShape", "center", "radius", "pitch", "turns", "pointsPerTurn", "tilt"}},
      {"pin", {"name", "s", "target", "keyframes"}},
      {"attachment", {"name", "s", "body", "localPoint", "stiffness", "damping"}},
      {"clamp", {"name", "s", "body", "localPoint", "localDirection", "stiffness", "damping", "angularStiffness", "angularDamping"}},
      {"winch", {"end", "speed", "restLength", "start"}},
      {"event",
       {"type", "time", "until", "rope", "body", "attachment", "s", "s0", "s1", "force", "forcePerLength", "linearVelocity",
        "angularVelocity", "name"}},
      {"check",
       {"name", "type", "from", "to", "at", "rope", "body", "attachment", "s", "winch", "mode", "min", "max", "box",
        "target", "localPoint"}},
      {"box", {"min", "max"}},
  };
  return tables;
}

const SceneFileKeyTable& sceneFileKeys(const std::string& object) {
  for (const SceneFileKeyTable& table : sceneFileKeyTables()) {
    if (table.object == object) return table;
  }
  throw std::logic_error("no scene-file key table '" + object + "'");
}

namespace {

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

// Levenshtein distance, O(|a| |b|) with one row.
std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string nearestKey(const std::string& key, const std::vector<std::string>& candidates) {
  const std::string wanted = lower(key);
  std::string best;
  std::size_t bestDistance = 0;
  for (const std::string& candidate : candidates) {
    const std::size_t distance = editDistance(wanted, lower(candidate));
    if (best.empty() || distance < bestDistance) {
      best = candidate;
      bestDistance = distance;
    }
  }
  const std::size_t longer = std::max(key.size(), best.size());
  return !best.empty() && 3 * bestDistance <= longer ? best : std::string();
}

}  // namespace rope::demos
