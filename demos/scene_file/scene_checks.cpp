// SPDX-License-Identifier: MIT
#include "demos/scene_file/scene_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "demos/scene_file/file_scene.h"
#include "demos/scenes/knot_scene.h"

namespace rope::demos {

namespace {

const char* typeName(CheckDescription::Kind kind) {
  switch (kind) {
    case CheckDescription::Kind::kPenetration: return "penetration";
    case CheckDescription::Kind::kContact: return "contact";
    case CheckDescription::Kind::kTension: return "tension";
    case CheckDescription::Kind::kPosition: return "position";
    case CheckDescription::Kind::kSlip: return "slip";
    case CheckDescription::Kind::kHealth: return "health";
    case CheckDescription::Kind::kKnotLength: return "knotLength";
  }
  return "?";
}

const char* unitOf(const CheckDescription& check) {
  switch (check.kind) {
    case CheckDescription::Kind::kContact: return "contacts";
    case CheckDescription::Kind::kTension: return "N";
    case CheckDescription::Kind::kHealth: return "warnings";
    default: return "m";
  }
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

std::string boundText(const CheckDescription& check) {
  switch (check.kind) {
    case CheckDescription::Kind::kContact: return check.never ? "<= 0" : ">= 1";
    case CheckDescription::Kind::kHealth: return "<= 0";
    case CheckDescription::Kind::kPosition: return check.boxMin ? "<= 0 (outside the box)" : "<= " + number(*check.max);
    case CheckDescription::Kind::kTension:
      if (check.min && check.max) return "in [" + number(*check.min) + ", " + number(*check.max) + "]";
      return check.min ? ">= " + number(*check.min) : "<= " + number(*check.max);
    default: return "<= " + number(*check.max);
  }
}

Vec3 fromBullet(const btVector3& v) { return Vec3(v.x(), v.y(), v.z()); }

// The rope parameter nearest to p: the nearest of 256 samples, refined by golden-section search over
// the two sample intervals around it (the distance is smooth and unimodal there).
double nearestParameter(const Rod& rod, const Vec3& p) {
  constexpr int kSamples = 256;
  const double a = rod.beginParameter(), b = rod.endParameter();
  auto at = [&](int i) { return std::min(b, a + (b - a) * i / kSamples); };
  int best = 0;
  double bestDistance = (rod.position(a) - p).squaredNorm();
  for (int i = 1; i <= kSamples; ++i) {
    const double d = (rod.position(at(i)) - p).squaredNorm();
    if (d < bestDistance) best = i, bestDistance = d;
  }
  double lo = at(std::max(0, best - 1)), hi = at(std::min(kSamples, best + 1));
  constexpr double kGolden = 0.6180339887498949;
  for (int iteration = 0; iteration < 40; ++iteration) {
    const double m1 = hi - kGolden * (hi - lo), m2 = lo + kGolden * (hi - lo);
    if ((rod.position(m1) - p).squaredNorm() < (rod.position(m2) - p).squaredNorm()) {
      hi = m2;
    } else {
      lo = m1;
    }
  }
  return 0.5 * (lo + hi);
}

long warnings(const FileScene& scene, const std::string& rope) {
  if (!rope.empty()) {
    const bullet::RopeObject* object = scene.findRope(rope);
    return object == nullptr ? 0 : object->warnings().total();
  }
  long total = scene.physics().ropes().warnings().total();
  for (const bullet::RopeObject* object : scene.physics().ropes().ropes()) total += object->warnings().total();
  return total;
}

}  // namespace

SceneChecks::SceneChecks(std::vector<CheckDescription> checks) : checks_(std::move(checks)) {
  for (const CheckDescription& check : checks_) {
    CheckResult result;
    result.name = check.name;
    result.type = typeName(check.kind);
    result.unit = unitOf(check);
    result.bound = boundText(check);
    results_.push_back(result);
  }
  states_.resize(checks_.size());
}

double SceneChecks::margin(const CheckDescription& check, double value) const {
  switch (check.kind) {
    case CheckDescription::Kind::kContact: return check.never ? -value : value - 1.0;
    case CheckDescription::Kind::kHealth: return -value;
    case CheckDescription::Kind::kPosition: return check.boxMin ? -value : *check.max - value;
    case CheckDescription::Kind::kTension: {
      double m = std::numeric_limits<double>::infinity();
      if (check.min) m = std::min(m, value - *check.min);
      if (check.max) m = std::min(m, *check.max - value);
      return m;
    }
    default: return *check.max - value;
  }
}

bool SceneChecks::measure(std::size_t i, const FileScene& scene, double& value) {
  const CheckDescription& check = checks_[i];
  State& state = states_[i];
  const bullet::RopeObject* rope = scene.findRope(check.rope);
  const btRigidBody* body = scene.findBody(check.body);
  if (!check.rope.empty() && rope == nullptr) return false;
  switch (check.kind) {
    case CheckDescription::Kind::kPenetration: {
      value = 0.0;
      for (const bullet::RopeContactRecord& contact : rope->contacts()) {
        if (contact.active && (body == nullptr || contact.body == body)) value = std::max(value, contact.depth);
      }
      return true;
    }
    case CheckDescription::Kind::kContact: {
      int count = 0;
      for (const bullet::RopeContactRecord& contact : rope->contacts()) count += contact.active && contact.body == body;
      value = count;
      return true;
    }
    case CheckDescription::Kind::kTension: {
      if (check.winch) {
        value = rope->winchTension(*check.winch);
      } else if (!check.attachment.empty()) {
        const std::optional<int> id = scene.attachmentId(check.rope, check.attachment);
        if (!id) return false;  // released
        value = rope->attachmentTension(*id);
      } else {
        const double s = FileScene::parameter(*rope, *check.s);
        if (s < rope->rod().beginParameter() || s > rope->rod().endParameter()) return false;  // cut away
        value = rope->tension(s);
      }
      return true;
    }
    case CheckDescription::Kind::kPosition: {
      Vec3 p;
      if (rope != nullptr) {
        const double s = FileScene::parameter(*rope, *check.s);
        if (s < rope->rod().beginParameter() || s > rope->rod().endParameter()) return false;
        p = rope->rod().position(s);
      } else {
        const btVector3 local(static_cast<btScalar>(check.localPoint.x()), static_cast<btScalar>(check.localPoint.y()),
                              static_cast<btScalar>(check.localPoint.z()));
        p = fromBullet(body->getWorldTransform() * local);
      }
      if (check.boxMin) {
        const Vec3 outside = (*check.boxMin - p).cwiseMax(p - *check.boxMax).cwiseMax(Vec3::Zero());
        value = outside.norm();
      } else {
        value = (p - *check.target).norm();
      }
      return true;
    }
    case CheckDescription::Kind::kSlip: {
      const btVector3 local(static_cast<btScalar>(check.localPoint.x()), static_cast<btScalar>(check.localPoint.y()),
                            static_cast<btScalar>(check.localPoint.z()));
      const double s = nearestParameter(rope->rod(), fromBullet(body->getWorldTransform() * local));
      if (!state.started) state.baseline = s;
      value = std::abs(s - state.baseline);
      return true;
    }
    case CheckDescription::Kind::kHealth: {
      // observe() keeps the count of the warnings of the window's steps (state.accumulated).
      value = state.accumulated;
      return true;
    }
    case CheckDescription::Kind::kKnotLength: {
      const KnotRegion region = knotRegion(*rope, scene.physics().ropes().lastReport());
      value = region.found ? region.length : 0.0;
      return true;
    }
  }
  return false;
}

Vec3 SceneChecks::marker(std::size_t i, const FileScene& scene) const {
  const CheckDescription& check = checks_[i];
  const bullet::RopeObject* rope = scene.findRope(check.rope);
  const btRigidBody* body = scene.findBody(check.body);
  const btVector3 local(static_cast<btScalar>(check.localPoint.x()), static_cast<btScalar>(check.localPoint.y()),
                        static_cast<btScalar>(check.localPoint.z()));
  if (check.kind == CheckDescription::Kind::kPenetration || (check.kind == CheckDescription::Kind::kContact && check.never)) {
    // The deepest active contact with the body.
    const bullet::RopeContactRecord* deepest = nullptr;
    for (const bullet::RopeContactRecord& contact : rope->contacts()) {
      if (contact.active && (body == nullptr || contact.body == body) && (deepest == nullptr || contact.depth > deepest->depth)) {
        deepest = &contact;
      }
    }
    if (deepest != nullptr) return fromBullet(deepest->point);
  }
  if (body != nullptr && (check.kind != CheckDescription::Kind::kPenetration || rope == nullptr)) {
    return fromBullet(body->getWorldTransform() * local);
  }
  if (rope == nullptr) return Vec3::Zero();
  const Rod& rod = rope->rod();
  double s = 0.5 * (rod.beginParameter() + rod.endParameter());
  if (check.s) {
    s = FileScene::parameter(*rope, *check.s);
  } else if (check.winch) {
    s = *check.winch == bullet::RopeEnd::kBegin ? rod.beginParameter() : rod.endParameter();
  } else if (!check.attachment.empty()) {
    if (const std::optional<int> id = scene.attachmentId(check.rope, check.attachment)) {
      for (const bullet::Attachment& attachment : rope->attachments()) {
        if (attachment.id == *id) s = attachment.s;
      }
    }
  } else if (check.kind == CheckDescription::Kind::kKnotLength) {
    const KnotRegion region = knotRegion(*rope, scene.physics().ropes().lastReport());
    if (region.found) s = 0.5 * (region.begin + region.end);
  }
  return rod.position(std::clamp(s, rod.beginParameter(), rod.endParameter()));
}

void SceneChecks::observe(const FileScene& scene) {
  const double t = scene.time();
  const double h = scene.timeStep();
  newFailures_.clear();
  for (std::size_t i = 0; i < checks_.size(); ++i) {
    const CheckDescription& check = checks_[i];
    if (check.kind == CheckDescription::Kind::kHealth) {
      // Warnings are counted since each rope was created; what this step added is the difference.
      const double total = static_cast<double>(warnings(scene, check.rope));
      const bool inWindow = t >= check.from - 0.5 * h && t <= check.to + 0.5 * h;
      if (inWindow) states_[i].accumulated += total - states_[i].previousTotal;
      states_[i].previousTotal = total;
    }
    if (check.at) {
      if (std::abs(t - *check.at) > 0.5 * h) continue;  // the step that ends nearest to `at`
    } else if (t < check.from - 0.5 * h || t > check.to + 0.5 * h) {
      continue;
    }
    double value = 0.0;
    if (!measure(i, scene, value)) continue;
    states_[i].started = true;
    CheckResult& result = results_[i];
    result.latest = value;
    ++result.samples;
    const double m = margin(check, value);
    if (m < 0.0 && std::isnan(result.firstFailureTime)) {
      result.firstFailureTime = t;
      result.marker = marker(i, scene);
      newFailures_.push_back(i);
    }
    if (m < result.worstMargin) {
      result.worstMargin = m;
      result.worst = value;
      result.worstTime = t;
    }
  }
}

void SceneChecks::finish(double endTime) {
  for (CheckResult& result : results_) {
    char line[256];
    if (result.samples == 0) {
      result.passed = false;
      std::snprintf(line, sizeof line, "not evaluated: no step of the run (0 to %.6g s) falls in its window", endTime);
    } else {
      result.passed = result.worstMargin >= 0.0;
      std::snprintf(line, sizeof line, "%s: worst %s %s at t = %.6g s, bound %s %s", result.passed ? "holds" : "FAILS",
                    number(result.worst).c_str(), result.unit.c_str(), result.worstTime, result.bound.c_str(),
                    result.unit.c_str());
    }
    result.message = line;
  }
}

bool SceneChecks::passed() const {
  return std::all_of(results_.begin(), results_.end(), [](const CheckResult& r) { return r.passed; });
}

}  // namespace rope::demos
