// SPDX-License-Identifier: MIT
// MuJoCo 2.2 side: <composite type="rope"> — a chain of capsule bodies joined by two hinges each
// (MuJoCo 2.2.2 has no `cable` plugin), built as an XML string and loaded from a virtual file.
// What matches and what cannot: length, mass (per link), radius, gravity and time step match; the
// links are rigid, so the chain cannot stretch unless Setting::stretch adds the composite's slide
// joints with stiffness EA / link length; no bending stiffness; mass damping c is applied exactly
// as a force -c m v on every link (xfrc_applied, from the previous step's velocities). The second pin
// of the catenary is a `connect` equality to a mocap body (a soft constraint: MuJoCo has no hard
// loop closure). Contacts: capsule-box and capsule-plane, MuJoCo's default soft contact; the rope
// does not collide with itself (it does not in the other engines either).

#include <mujoco/mujoco.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include "demos/compare/runners.h"
#include "demos/compare/scene_specs.h"
#include "rope/common/error.h"

namespace rope::compare::mujoco {
namespace {

using Clock = std::chrono::steady_clock;

// Where the rope starts and how it is held.
struct RopeLayout {
  int links = 16;
  double length = 1.0;         // m
  double radius = 0.01;        // m
  double linearDensity = 0.1;  // kg/m
  double axialStiffness = 0;   // N (EA), used with stretch
  double axialDamping = 0;     // s (stiffness-proportional damping of the slide joints)
  Eigen::Vector3d start{0, 0, 0};
  double angleDegrees = 0;     // rotation about z of the rope's direction (0: +x, -90: -y)
  std::string rootJoint = "free";  // "free" or "ball" (pinned start)
  bool pinStartToMocap = false;    // the root body is a child of mocap body "pinA"
  bool pinEndToMocap = false;      // connect equality from the rope's end to mocap body "pinB"
  double endLoadMass = 0;          // kg: a cube hung from the rope's end (buildLoadedChainXml)
  double endLoadHalf = 0.1;        // m
  std::string obstacles;           // extra <worldbody> XML
  bool stretch = false;
};

std::string buildXml(const RopeLayout& rope, double timestep) {
  const double spacing = rope.length / rope.links;
  const double half = 0.5 * spacing;
  const double angle = rope.angleDegrees * M_PI / 180.0;
  const Eigen::Vector3d direction(std::cos(angle), std::sin(angle), 0);
  const Eigen::Vector3d root = rope.start + half * direction;
  std::ostringstream xml;
  xml.precision(17);
  xml << "<mujoco><option timestep='" << timestep << "' gravity='0 -9.81 0'/>"
      // Constraint buffers: MuJoCo 2.2 allocates njmax x nv dense rows, so size them to the scene.
      << "<size nconmax='" << (rope.obstacles.empty() ? 10 : 8 * rope.links + 200) << "' njmax='"
      << (rope.obstacles.empty() ? 50 : 40 * rope.links + 1000) << "'/>"
      << "<worldbody>" << rope.obstacles;
  const Eigen::Vector3d end = rope.start + rope.length * direction;
  if (rope.pinEndToMocap) {
    xml << "<body name='pinB' mocap='true' pos='" << end.x() << ' ' << end.y() << ' ' << end.z() << "'/>";
  }
  if (rope.pinStartToMocap) {
    xml << "<body name='pinA' mocap='true' pos='" << rope.start.x() << ' ' << rope.start.y() << ' ' << rope.start.z()
        << "'>";
  }
  const Eigen::Vector3d rootLocal = rope.pinStartToMocap ? Eigen::Vector3d(root - rope.start) : root;
  xml << "<body name='RB0' pos='" << rootLocal.x() << ' ' << rootLocal.y() << ' ' << rootLocal.z()
      << "' axisangle='0 0 1 " << rope.angleDegrees << "'>";
  if (rope.rootJoint == "free") xml << "<freejoint/>";
  else xml << "<joint type='ball' pos='" << -half << " 0 0'/>";
  xml << "<composite type='rope' count='" << rope.links << " 1 1' spacing='" << spacing << "' prefix='R'>"
      << "<joint kind='main' damping='0'/>";
  if (rope.stretch) {
    const double stiffness = rope.axialStiffness / spacing;
    xml << "<joint kind='stretch' stiffness='" << stiffness << "' damping='" << rope.axialDamping * stiffness << "'/>";
  }
  xml << "<geom type='capsule' size='" << rope.radius << ' ' << half << "' mass='" << rope.linearDensity * spacing
      << "' contype='1' conaffinity='2' friction='0.5 0.005 0.0001'/></composite></body>";
  if (rope.pinStartToMocap) xml << "</body>";
  xml << "</worldbody><equality>";
  if (rope.pinEndToMocap)
    xml << "<connect body1='RB" << rope.links - 1 << "' body2='pinB' anchor='" << half << " 0 0'/>";
  xml << "</equality>";
  xml << "</mujoco>";
  return xml.str();
}

// The heavy-load rope as an explicit chain of nested bodies (ball joint + optional axial slide
// joint per link) with the load cube nested in the last link by a ball joint. A composite rope cannot
// carry the load exactly: its bodies cannot be nested into, and a `connect` equality from a 0.6 g
// link to a 10 kg box is so soft (MuJoCo scales constraint softness by the effective mass) that the
// box slid 1.9 m away. tinyxml2 limits nesting depth, so this serves short chains only (<= 64 links).
std::string buildLoadedChainXml(const RopeLayout& rope, double timestep) {
  const double spacing = rope.length / rope.links;
  const double half = 0.5 * spacing;
  const double angle = rope.angleDegrees * M_PI / 180.0;
  const Eigen::Vector3d root = rope.start + half * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0);
  const double stiffness = rope.axialStiffness / spacing;
  std::ostringstream xml;
  xml.precision(17);
  xml << "<mujoco><option timestep='" << timestep << "' gravity='0 -9.81 0'/><worldbody>";
  for (int i = 0; i < rope.links; ++i) {
    xml << "<body name='RB" << i << "' ";
    if (i == 0) xml << "pos='" << root.x() << ' ' << root.y() << ' ' << root.z() << "' axisangle='0 0 1 " << rope.angleDegrees << "'>";
    else xml << "pos='" << spacing << " 0 0'>";
    xml << "<joint type='ball' pos='" << -half << " 0 0'/>";
    if (rope.stretch)
      xml << "<joint type='slide' axis='1 0 0' stiffness='" << stiffness << "' damping='" << rope.axialDamping * stiffness << "'/>";
    xml << "<geom type='capsule' fromto='" << -half << " 0 0 " << half << " 0 0' size='" << rope.radius << "' mass='"
        << rope.linearDensity * spacing << "' contype='1' conaffinity='2'/>";
  }
  xml << "<body name='load' pos='" << half + rope.endLoadHalf << " 0 0'><joint type='ball' pos='" << -rope.endLoadHalf
      << " 0 0'/><geom type='box' size='" << rope.endLoadHalf << ' ' << rope.endLoadHalf << ' ' << rope.endLoadHalf
      << "' mass='" << rope.endLoadMass << "' contype='0' conaffinity='0'/></body>";
  for (int i = 0; i < rope.links; ++i) xml << "</body>";
  xml << "</worldbody></mujoco>";
  return xml.str();
}

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};

void quietWarning(const char*) {}

std::unique_ptr<mjModel, ModelDeleter> loadModel(const std::string& xml) {
  mju_user_warning = quietWarning;  // instability is detected through d->warning and reported
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), "rope.xml", static_cast<int>(xml.size())) != 0)
    throw std::runtime_error("mujoco: cannot create the virtual model file");
  const int index = mj_findFileVFS(vfs.get(), "rope.xml");
  std::memcpy(vfs->filedata[index], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* model = mj_loadXML("rope.xml", vfs.get(), error, sizeof error);
  mj_deleteVFS(vfs.get());
  if (!model) throw std::runtime_error(std::string("mujoco: model did not load: ") + error);
  return std::unique_ptr<mjModel, ModelDeleter>(model);
}

class Chain {
 public:
  Chain(const RopeLayout& layout, double h, int substeps) : layout_(layout), substeps_(substeps) {
    model_ = loadModel(layout.endLoadMass > 0 ? buildLoadedChainXml(layout, h / substeps) : buildXml(layout, h / substeps));
    data_.reset(mj_makeData(model_.get()));
    for (int b = 0; b < layout.links; ++b) {
      const std::string name = "RB" + std::to_string(b);
      bodies_.push_back(mj_name2id(model_.get(), mjOBJ_BODY, name.c_str()));
      if (bodies_.back() < 0) throw std::runtime_error("mujoco: no body " + name);
    }
    for (int j = 0; j < model_->njnt; ++j)
      if (model_->jnt_type[j] == mjJNT_SLIDE) slides_.push_back(model_->jnt_qposadr[j]);
    // The composite also ties each stretch joint to zero with a soft joint equality; switched off,
    // the slide joints' springs (EA / link length) alone carry the axial load, as in a rod.
    if (layout.stretch)
      for (int e = 0; e < model_->neq; ++e)
        if (model_->eq_type[e] == mjEQ_JOINT) model_->eq_active[e] = 0;
    if (model_->nmocap > 0) mocapA_ = mocapIndex("pinA"), mocapB_ = mocapIndex("pinB");
    mj_forward(model_.get(), data_.get());
  }

  // One scene step: `substeps` mj_step calls with mass damping; false if MuJoCo reported instability.
  bool step(double massDamping) {
    for (int k = 0; k < substeps_; ++k) {
      if (massDamping > 0) {
        for (int b : bodies_) {
          mjtNum velocity[6];
          mj_objectVelocity(model_.get(), data_.get(), mjOBJ_BODY, b, velocity, 0);
          const double m = model_->body_mass[b];
          for (int a = 0; a < 3; ++a) data_->xfrc_applied[6 * b + a] = -massDamping * m * velocity[3 + a];
        }
      }
      mj_step(model_.get(), data_.get());
      if (data_->warning[mjWARN_BADQACC].number > 0) return false;
    }
    return true;
  }

  void setMocap(int index, const Eigen::Vector3d& p) {
    if (index < 0) return;
    for (int a = 0; a < 3; ++a) data_->mocap_pos[3 * index + a] = p[a];
  }
  int mocapA() const { return mocapA_; }
  int mocapB() const { return mocapB_; }
  int dofs() const { return model_->nv; }

  // Ends of link b's centre line.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> link(int b) const {
    const int id = bodies_[b];
    const Eigen::Vector3d centre(data_->xpos[3 * id], data_->xpos[3 * id + 1], data_->xpos[3 * id + 2]);
    // Column 0 of xmat is the body's x axis (the composite lays links along x).
    const Eigen::Vector3d axis(data_->xmat[9 * id], data_->xmat[9 * id + 3], data_->xmat[9 * id + 6]);
    const double half = 0.5 * layout_.length / layout_.links;
    return {centre - half * axis, centre + half * axis};
  }
  template <class F>
  void forEachPoint(int perLink, F f) const {
    for (int b = 0; b < layout_.links; ++b) {
      const auto [p, q] = link(b);
      for (int k = 0; k <= perLink; ++k) f(p + (q - p) * (double(k) / perLink));
    }
  }
  // Rope length: the links plus the stretch of the slide joints.
  double length() const {
    double length = layout_.length;
    for (int address : slides_) length += data_->qpos[address];
    return length;
  }

 private:
  int mocapIndex(const char* name) const {
    const int body = mj_name2id(model_.get(), mjOBJ_BODY, name);
    return body < 0 ? -1 : model_->body_mocapid[body];
  }

  RopeLayout layout_;
  int substeps_ = 1;
  std::unique_ptr<mjModel, ModelDeleter> model_;
  std::unique_ptr<mjData, DataDeleter> data_;
  std::vector<int> bodies_;
  std::vector<int> slides_;
  int mocapA_ = -1, mocapB_ = -1;
};

void validate(const Setting& setting) {
  if (setting.resolution < 2) throw InvalidArgument("setting.resolution", std::to_string(setting.resolution), "must be >= 2 links");
  if (setting.substeps < 1) throw InvalidArgument("setting.substeps", std::to_string(setting.substeps), "must be >= 1");
}

template <class Before, class After>
void runChain(Chain& chain, double h, int steps, double massDamping, double wallBudget, Trial& trial, Before before,
              After after) {
  for (int i = 1; i <= steps; ++i) {
    before(i * h);
    const auto start = Clock::now();
    const bool ok = chain.step(massDamping);
    trial.stepSeconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    trial.wallSeconds += trial.stepSeconds.back();
    trial.steps = i;
    trial.simulatedSeconds = i * h;
    if (!ok) {
      trial.status = "exploded";
      return;
    }
    if (trial.wallSeconds > wallBudget) {
      trial.status = "too slow";
      return;
    }
    after(i * h);
  }
}

Trial catenary(const Setting& setting, const Limits& limits, bool timePerStepOnly) {
  CatenarySpec spec;
  ScalingSpec scaling;
  const demos::HangSceneSettings& hang = spec.hang;
  RodSettings rod = hang.rod;
  rod.restLength = hang.ropeLength;
  RopeLayout layout;
  layout.links = setting.resolution;
  layout.length = hang.ropeLength;
  layout.radius = rod.radius;
  layout.linearDensity = rod.effectiveLinearDensity();
  layout.start = {-0.5 * hang.ropeLength, hang.pinHeight, 0};
  layout.rootJoint = "ball";
  layout.pinStartToMocap = layout.pinEndToMocap = true;
  const double h = hang.timeStep;
  Chain chain(layout, h, setting.substeps);
  const double duration = limits.seconds > 0 ? limits.seconds : spec.seconds;
  const int steps = timePerStepOnly ? scaling.warmupSteps + scaling.maxSteps : static_cast<int>(std::lround(duration / h));
  Trial trial;
  double sagSum = 0;
  int samples = 0;
  runChain(
      chain, h, steps, rod.massDamping, timePerStepOnly ? std::min(limits.wallBudget, scaling.wallBudget) : limits.wallBudget,
      trial,
      [&](double t) {
        const double x = 0.5 * spec.pinDistance(t);
        chain.setMocap(chain.mocapA(), {-x, hang.pinHeight, 0});
        chain.setMocap(chain.mocapB(), {x, hang.pinHeight, 0});
      },
      [&](double t) {
        if (timePerStepOnly || t <= duration - spec.averagingWindow) return;
        double lowest = hang.pinHeight;
        chain.forEachPoint(1, [&](const Eigen::Vector3d& p) { lowest = std::min(lowest, p.y()); });
        sagSum += hang.pinHeight - lowest;
        ++samples;
      });
  if (timePerStepOnly && trial.status == "too slow" && trial.steps >= 2) trial.status = "ok";
  trial.dofs = chain.dofs();
  if (samples > 0 && trial.ok()) {
    trial.metrics["sag_m"] = sagSum / samples;
    trial.metrics["sag_error"] = sagSum / samples / spec.analyticSag() - 1.0;
  }
  return trial;
}

Trial heavyLoad(const Setting& setting, const Limits& limits) {
  HeavyLoadSpec spec;
  if (limits.loadMass > 0) spec.crane.boxMass = limits.loadMass;
  const demos::CraneSceneSettings& crane = spec.crane;
  RodSettings rod = crane.rod;
  rod.restLength = crane.ropeLength;
  RopeLayout layout;
  layout.links = setting.resolution;
  layout.length = crane.ropeLength;
  layout.radius = rod.radius;
  layout.linearDensity = rod.effectiveLinearDensity();
  layout.axialStiffness = rod.axialStiffness();
  layout.axialDamping = rod.stiffnessDamping;
  layout.start = {0, crane.topHeight, 0};
  layout.angleDegrees = -90;
  layout.rootJoint = "ball";
  layout.stretch = setting.stretch;
  // The 10 kg box hangs from the rope's end by a ball joint (an explicit chain, see buildLoadedChainXml).
  layout.endLoadMass = crane.boxMass;
  const double h = crane.timeStep;
  Chain chain(layout, h, setting.substeps);
  const double duration = limits.seconds > 0 ? limits.seconds : spec.seconds;
  Trial trial;
  double strainSum = 0;
  int samples = 0;
  runChain(
      chain, h, static_cast<int>(std::lround(duration / h)), rod.massDamping, limits.wallBudget, trial, [](double) {},
      [&](double t) {
        if (t <= duration - spec.averagingWindow) return;
        strainSum += chain.length() / crane.ropeLength - 1.0;
        ++samples;
      });
  trial.dofs = chain.dofs();
  if (samples > 0 && trial.ok()) {
    trial.metrics["strain"] = strainSum / samples;
    trial.metrics["strain_error"] = strainSum / samples / spec.expectedStrain() - 1.0;
  }
  return trial;
}

Trial drape(const DrapeSpec& spec, const Setting& setting, const Limits& limits) {
  const demos::DrapeSceneSettings& drape = spec.drape;
  RodSettings rod = drape.rod;
  rod.restLength = drape.ropeLength;
  RopeLayout layout;
  layout.links = setting.resolution;
  layout.length = drape.ropeLength;
  layout.radius = rod.radius;
  layout.linearDensity = rod.effectiveLinearDensity();
  const double y = drape.obstacleTop + drape.dropHeight + rod.radius;
  layout.start = {-0.5 * drape.ropeLength, y, 0};
  const Eigen::Vector3d c = spec.obstacleCentre(), e = spec.obstacleHalfExtents();
  std::ostringstream obstacles;
  obstacles.precision(17);
  obstacles << "<geom type='plane' size='5 5 0.1' zaxis='0 1 0' contype='2' conaffinity='1' friction='0.5 0.005 0.0001'/>"
            << "<geom type='box' pos='" << c.x() << ' ' << c.y() << ' ' << c.z() << "' size='" << e.x() << ' ' << e.y()
            << ' ' << e.z() << "' contype='2' conaffinity='1' friction='0.5 0.005 0.0001'/>";
  layout.obstacles = obstacles.str();
  const double h = drape.timeStep;
  Chain chain(layout, h, setting.substeps);
  const double duration = limits.seconds > 0 ? limits.seconds : spec.seconds;
  Trial trial;
  DrapePenetration penetration(spec, duration);
  runChain(
      chain, h, static_cast<int>(std::lround(duration / h)), rod.massDamping, limits.wallBudget, trial, [](double) {},
      [&](double t) { penetration.sample(t, [&](const auto& visit) { chain.forEachPoint(4, visit); }); });
  double highest = -1e9;
  chain.forEachPoint(1, [&](const Eigen::Vector3d& p) { highest = std::max(highest, p.y()); });
  trial.dofs = chain.dofs();
  penetration.record(trial.metrics);
  trial.metrics["highest_m"] = highest;
  return trial;
}

}  // namespace

Trial run(Scene scene, const Setting& setting, const Limits& limits) {
  validate(setting);
  switch (scene) {
    case Scene::kCatenary: return catenary(setting, limits, false);
    case Scene::kHeavyLoad: return heavyLoad(setting, limits);
    case Scene::kThinBar: return drape(DrapeSpec::thinBar(), setting, limits);
    case Scene::kDrape: return drape(DrapeSpec::box(), setting, limits);
    case Scene::kScaling: return catenary(setting, limits, true);
  }
  return Trial{};
}

}  // namespace rope::compare::mujoco
