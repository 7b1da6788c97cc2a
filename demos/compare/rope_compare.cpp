// SPDX-License-Identifier: MIT
// rope_compare [--quick] [--out PREFIX] [--repeats N] [--check README]
// rope_compare --try ENGINE SCENE RESOLUTION ITERATIONS SUBSTEPS STRETCH(0/1) SECONDS
//
// Runs the five comparison scenes (compare.h) with SplineRope, Bullet's soft-body rope and a MuJoCo
// chain, sweeping each peer's resolution and solver setting, and writes PREFIX.json (every trial),
// PREFIX.md (the summary table and the whole sweep) and PREFIX.dat (accuracy against cost, for
// demos/compare/plot.gp). Wall time per simulated second is the median over --repeats runs made in
// this one process, the engines alternating within each round. --quick is the smoke run for the
// default tests (quickPlan): few settings, short runs but for the heavy load and the thin bar. Every
// run fails (exit 1) if SplineRope fails a scene (a step failure, or the thin bar not held); with
// --check README it also fails unless the run bears out the README table's heavy-load and thin-bar
// claims (checkClaims), naming each claim that failed and the value measured.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>

#include "demos/compare/compare.h"
#include "demos/compare/scene_specs.h"

namespace rope::compare {
namespace {

constexpr double kTargetError = 0.01;  // "equal accuracy": |sag error| and |strain error| within 1 %

struct Entry {
  Engine engine;
  Scene scene;
  Setting setting;
  Trial trial;                 // the first run (accuracy; all engines are deterministic)
  std::vector<double> costs;   // wall s per simulated s, one per repeat
  std::vector<double> stepUs;  // wall us per step, one per repeat
  double medianCost() const { return median(costs); }
  double medianStepUs() const { return median(stepUs); }
  static double median(std::vector<double> v) {
    if (v.empty()) return kNaN;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  }
};

Setting res(int resolution, int iterations = 1, int substeps = 1, bool stretch = false) {
  Setting s;
  s.resolution = resolution;
  s.iterations = iterations;
  s.substeps = substeps;
  s.stretch = stretch;
  return s;
}

struct Plan {
  Scene scene;
  Limits limits;
  std::map<Engine, std::vector<Setting>> settings;
};

std::vector<Plan> fullPlan(double wallBudget) {
  std::vector<Plan> plans;
  Limits limits;
  limits.wallBudget = wallBudget;
  {
    Plan p{Scene::kCatenary, limits, {}};
    p.settings[Engine::kSplineRope] = {res(6), res(8), res(12), res(16)};
    for (int n : {16, 32, 64, 128})
      for (int it : {1, 4, 16, 64, 256}) p.settings[Engine::kSoftBody].push_back(res(n, it));
    for (int n : {8, 16, 32, 64})
      for (int sub : {1, 4}) p.settings[Engine::kMuJoCo].push_back(res(n, 1, sub));
    plans.push_back(p);
  }
  {
    Plan p{Scene::kHeavyLoad, limits, {}};
    p.settings[Engine::kSplineRope] = {res(8), res(12)};
    for (int n : {8, 16, 32, 64})
      for (int it : {4, 16, 64, 256}) p.settings[Engine::kSoftBody].push_back(res(n, it));
    // Position-based links converge to inextensible with iterations; follow the coarsest rope further.
    for (int it : {1024, 4096}) p.settings[Engine::kSoftBody].push_back(res(8, it));
    p.settings[Engine::kSoftBody].push_back(res(16, 1024));
    p.settings[Engine::kMuJoCo] = {res(16), res(16, 1, 16)};  // inextensible links
    for (int n : {4, 8, 16})
      for (int sub : {1, 4, 16, 64}) p.settings[Engine::kMuJoCo].push_back(res(n, 1, sub, true));
    plans.push_back(p);
  }
  {
    Plan p{Scene::kThinBar, limits, {}};
    p.settings[Engine::kSplineRope] = {res(16)};
    for (int n : {16, 33, 64, 128}) p.settings[Engine::kSoftBody].push_back(res(n, 16));
    for (int n : {16, 33, 64}) p.settings[Engine::kMuJoCo].push_back(res(n));
    for (int n : {16, 33, 64}) p.settings[Engine::kMuJoCo].push_back(res(n, 1, 4));
    plans.push_back(p);
  }
  {
    Plan p{Scene::kDrape, limits, {}};
    p.settings[Engine::kSplineRope] = {res(16)};
    p.settings[Engine::kSoftBody] = {res(32, 16), res(64, 16)};
    p.settings[Engine::kMuJoCo] = {res(32), res(64), res(32, 1, 4)};
    plans.push_back(p);
  }
  return plans;
}

// The smoke run. Catenary and drape: one setting per engine, shortened. Heavy load and thin bar: the
// README table's settings at the scenes' full length (4 s and 2.5 s), so that --check can hold the
// run to the table's claims: the heavy load's cheapest setting within 1 % of each engine (the 5 kg
// load check then runs the same settings), and every thin-bar setting of the table but MuJoCo's
// 64 links with 4 substeps (6 s of wall time for one more "fell through"). Keep these in step with
// the README table; --check names a setting the table states and this plan does not run.
std::vector<Plan> quickPlan() {
  std::vector<Plan> plans;
  auto limits = [](double seconds, double wallBudget) {
    Limits l;
    l.wallBudget = wallBudget;
    l.seconds = seconds;
    return l;
  };
  plans.push_back({Scene::kCatenary, limits(3.0, 4.0), {{Engine::kSplineRope, {res(12)}}, {Engine::kSoftBody, {res(32, 4)}}, {Engine::kMuJoCo, {res(16)}}}});
  plans.push_back({Scene::kHeavyLoad, limits(0.0, 15.0), {{Engine::kSplineRope, {res(8)}}, {Engine::kSoftBody, {res(8, 1792)}}, {Engine::kMuJoCo, {res(4, 1, 4, true)}}}});
  plans.push_back({Scene::kThinBar, limits(0.0, 15.0),
                   {{Engine::kSplineRope, {res(16)}},
                    {Engine::kSoftBody, {res(16, 16), res(33, 16), res(64, 16), res(128, 16)}},
                    {Engine::kMuJoCo, {res(16), res(33), res(64), res(16, 1, 4), res(33, 1, 4)}}}});
  plans.push_back({Scene::kDrape, limits(0.5, 4.0), {{Engine::kSplineRope, {res(16)}}, {Engine::kSoftBody, {res(32, 16)}}, {Engine::kMuJoCo, {res(32)}}}});
  return plans;
}

const std::vector<Engine> kEngines = {Engine::kSplineRope, Engine::kSoftBody, Engine::kMuJoCo};

// Runs every setting of a plan `repeats` times; each round visits the engines in turn (the first
// engine rotating from round to round), one setting of each at a time.
std::vector<Entry> runPlan(const Plan& plan, int repeats) {
  std::vector<Entry> entries;
  std::map<Engine, std::vector<size_t>> index;
  for (Engine e : kEngines)
    for (const Setting& s : plan.settings.at(e)) {
      index[e].push_back(entries.size());
      entries.push_back({e, plan.scene, s, Trial{}, {}, {}});
    }
  size_t longest = 0;
  for (Engine e : kEngines) longest = std::max(longest, plan.settings.at(e).size());
  for (int round = 0; round < repeats; ++round) {
    for (size_t i = 0; i < longest; ++i) {
      for (size_t k = 0; k < kEngines.size(); ++k) {
        const Engine e = kEngines[(k + round) % kEngines.size()];
        if (i >= index[e].size()) continue;
        Entry& entry = entries[index[e][i]];
        if (round > 0 && !entry.trial.ok()) continue;  // a failed or too slow run is not repeated
        const Trial trial = run(e, plan.scene, entry.setting, plan.limits);
        if (round == 0) entry.trial = trial;
        entry.costs.push_back(trial.costPerSecond());
        entry.stepUs.push_back(trial.stepMicroseconds());
      }
    }
  }
  return entries;
}

std::vector<Entry> runScaling(const std::vector<int>& sizes, int repeats, int softIterations, double wallBudget) {
  std::vector<Entry> entries;
  Limits limits;
  limits.wallBudget = wallBudget;
  for (int n : sizes)
    for (Engine e : kEngines)
      entries.push_back({e, Scene::kScaling, e == Engine::kSoftBody ? res(n, softIterations) : res(n), Trial{}, {}, {}});
  for (int round = 0; round < repeats; ++round)
    for (size_t i = 0; i < entries.size(); i += kEngines.size())
      for (size_t k = 0; k < kEngines.size(); ++k) {
        Entry& entry = entries[i + (k + round) % kEngines.size()];
        // The MuJoCo chain's dense 2n x 2n mass matrix makes n = 1024 cost seconds per step: time it once.
        if (round > 0 && (!entry.trial.ok() || entry.trial.wallSeconds > 2.0)) continue;
        const Trial trial = run(entry.engine, Scene::kScaling, entry.setting, limits);
        if (round == 0) entry.trial = trial;
        entry.costs.push_back(trial.costPerSecond());
        entry.stepUs.push_back(trial.medianStepMicroseconds());
      }
  return entries;
}

double metric(const Entry& e, const char* name) {
  const auto it = e.trial.metrics.find(name);
  return it == e.trial.metrics.end() ? kNaN : it->second;
}

// Runs an entry `repeats` times (the first run gives its accuracy).
Entry measure(Engine engine, Scene scene, const Setting& setting, const Limits& limits, int repeats) {
  Entry entry{engine, scene, setting, Trial{}, {}, {}};
  for (int round = 0; round < repeats; ++round) {
    const Trial trial = run(engine, scene, setting, limits);
    if (round == 0) entry.trial = trial;
    entry.costs.push_back(trial.costPerSecond());
    entry.stepUs.push_back(trial.stepMicroseconds());
    if (!trial.ok()) break;
  }
  return entry;
}

// The soft body's position-based links converge towards inextensible as iterations grow, so its
// strain falls from far above W/(EA) through it towards zero. Where two swept iteration counts of one
// resolution bracket the target, bisect the iteration count until a setting lands within 1 %: the
// cheapest "equal accuracy" soft body there is. It is a calibration to this load and time step, not
// a stiffness (the load check below runs it at another load).
std::vector<Entry> calibrateSoftBody(const std::vector<Entry>& heavy, const Limits& limits, int repeats) {
  std::map<int, std::vector<const Entry*>> byResolution;
  for (const Entry& e : heavy)
    if (e.engine == Engine::kSoftBody && e.trial.ok() && !std::isnan(metric(e, "strain_error")))
      byResolution[e.setting.resolution].push_back(&e);
  std::vector<Entry> found;
  for (auto& [resolution, entries] : byResolution) {
    std::sort(entries.begin(), entries.end(),
              [](const Entry* a, const Entry* b) { return a->setting.iterations < b->setting.iterations; });
    for (size_t i = 0; i + 1 < entries.size(); ++i) {
      const double a = metric(*entries[i], "strain_error"), b = metric(*entries[i + 1], "strain_error");
      if (!(a > kTargetError && b < kTargetError) || std::abs(b) <= kTargetError) continue;
      int low = entries[i]->setting.iterations, high = entries[i + 1]->setting.iterations;
      for (int probe = 0; probe < 14 && high - low > 1; ++probe) {
        Setting setting = entries[i]->setting;
        setting.iterations = (low + high) / 2;
        const Trial trial = run(Engine::kSoftBody, Scene::kHeavyLoad, setting, limits);
        const double error = trial.ok() ? trial.metrics.at("strain_error") : kNaN;
        std::fprintf(stderr, "           soft body %s: strain error %+.2f %%\n", setting.label().c_str(), 100 * error);
        if (std::abs(error) <= kTargetError) {
          found.push_back(measure(Engine::kSoftBody, Scene::kHeavyLoad, setting, limits, repeats));
          break;
        }
        if (error > 0) low = setting.iterations;
        else high = setting.iterations;
      }
    }
  }
  return found;
}

// The cheapest ok entry of an engine whose |metric| is within the target, or nullptr.
const Entry* cheapestWithin(const std::vector<Entry>& entries, Engine engine, const char* name) {
  const Entry* best = nullptr;
  for (const Entry& e : entries) {
    if (e.engine != engine || !e.trial.ok()) continue;
    const double err = metric(e, name);
    if (!(std::abs(err) <= kTargetError)) continue;
    if (!best || e.medianCost() < best->medianCost()) best = &e;
  }
  return best;
}

// The ok entry of an engine with the smallest |metric|, or nullptr.
const Entry* mostAccurate(const std::vector<Entry>& entries, Engine engine, const char* name) {
  const Entry* best = nullptr;
  for (const Entry& e : entries) {
    if (e.engine != engine || !e.trial.ok() || std::isnan(metric(e, name))) continue;
    if (!best || std::abs(metric(e, name)) < std::abs(metric(*best, name))) best = &e;
  }
  return best;
}

std::string fmt(const char* format, double value) {
  if (std::isnan(value)) return "n/a";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

std::string percent(double x) { return fmt("%+.2f %%", 100 * x); }
std::string ms(double seconds) { return fmt(seconds < 0.01 ? "%.2f" : seconds < 1 ? "%.1f" : "%.0f", 1e3 * seconds); }

std::string describeFailures(const std::vector<Entry>& entries, Engine engine) {
  std::map<std::string, int> counts;
  for (const Entry& e : entries)
    if (e.engine == engine && !e.trial.ok()) counts[e.trial.status] += 1;
  std::string text;
  for (const auto& [status, count] : counts) text += (text.empty() ? "" : ", ") + std::to_string(count) + " " + status;
  return text;
}

// "setting: error, cost ms/s" for the cheapest within target, or why there is none.
std::string accuracyCell(const std::vector<Entry>& entries, Engine engine, const char* name) {
  const Entry* best = cheapestWithin(entries, engine, name);
  std::ostringstream cell;
  if (best) {
    cell << best->setting.label() << " (" << best->trial.dofs << " dof): " << percent(metric(*best, name)) << ", "
         << ms(best->medianCost()) << " ms";
  } else {
    const Entry* closest = mostAccurate(entries, engine, name);
    cell << "**never within 1 %**";
    if (closest)
      cell << "; best " << closest->setting.label() << ": " << percent(metric(*closest, name)) << ", "
           << ms(closest->medianCost()) << " ms";
  }
  const std::string failures = describeFailures(entries, engine);
  if (!failures.empty()) cell << " [" << failures << " of the sweep]";
  return cell.str();
}

std::string ratioCell(const std::vector<Entry>& entries, Engine engine, const char* name) {
  const Entry* ours = cheapestWithin(entries, Engine::kSplineRope, name);
  const Entry* theirs = cheapestWithin(entries, engine, name);
  if (!ours) return "SplineRope not within 1 %";
  if (!theirs) return "no peer setting within 1 %";
  return fmt("%.1f×", theirs->medianCost() / ours->medianCost());
}

// A thin-bar trial's outcome: "held" (the rope's highest point at the end within 10 cm of the bar's
// top), "fell through", or how the run failed ("exploded", ...).
std::string thinBarOutcome(const Entry& e, double barTop) {
  if (!e.trial.ok()) return e.trial.status;
  return metric(e, "highest_m") > barTop - 0.1 ? "held" : "fell through";
}

std::string thinBarCell(const std::vector<Entry>& entries, Engine engine, double barTop) {
  std::string cell;
  for (const Entry& e : entries) {
    if (e.engine != engine) continue;
    cell += (cell.empty() ? "" : "; ") + e.setting.label() + ": " + thinBarOutcome(e, barTop);
  }
  return cell;
}

std::string drapeCell(const std::vector<Entry>& entries, Engine engine, double radius) {
  std::string cell;
  for (const Entry& e : entries) {
    if (e.engine != engine) continue;
    std::ostringstream text;
    text << e.setting.label() << ": ";
    if (!e.trial.ok()) text << e.trial.status;
    else
      text << fmt("%.2f", 1e3 * metric(e, "max_penetration_m")) << " / "
           << fmt("%.2f", 1e3 * metric(e, "resting_penetration_m")) << " mm ("
           << fmt("%.1f", 100 * metric(e, "resting_penetration_m") / radius) << " % of r)";
    cell += (cell.empty() ? "" : "; ") + text.str();
  }
  return cell;
}

void writeJsonString(std::ostream& out, const std::string& s) {
  out << '"';
  for (char c : s) {
    if (c == '"' || c == '\\') out << '\\' << c;
    else if (static_cast<unsigned char>(c) < 0x20) out << ' ';
    else out << c;
  }
  out << '"';
}

void writeJsonNumber(std::ostream& out, double x) {
  if (std::isfinite(x)) out << x;
  else out << "null";
}

void writeJson(const std::string& path, const std::vector<Entry>& entries, int repeats, double totalSeconds, bool quick,
               const std::map<std::string, std::string>& summary) {
  std::ofstream out(path);
  out.precision(6);
  out << "{\n  \"program\": \"rope_compare\",\n  \"quick\": " << (quick ? "true" : "false") << ",\n  \"repeats\": " << repeats
      << ",\n  \"mujoco_version\": ";
  writeJsonString(out, mj_versionString());
  out << ",\n  \"target_error\": " << kTargetError << ",\n  \"total_wall_s\": " << totalSeconds << ",\n  \"summary\": {";
  bool first = true;
  for (const auto& [key, value] : summary) {
    out << (first ? "\n    " : ",\n    ");
    writeJsonString(out, key);
    out << ": ";
    writeJsonString(out, value);
    first = false;
  }
  out << "\n  },\n  \"trials\": [";
  first = true;
  for (const Entry& e : entries) {
    out << (first ? "\n" : ",\n") << "    {\"scene\": \"" << sceneName(e.scene) << "\", \"engine\": \"" << engineName(e.engine)
        << "\", \"setting\": {\"resolution\": " << e.setting.resolution << ", \"iterations\": " << e.setting.iterations
        << ", \"substeps\": " << e.setting.substeps << ", \"stiffness\": " << e.setting.stiffness
        << ", \"stretch\": " << (e.setting.stretch ? "true" : "false") << "}, \"status\": ";
    writeJsonString(out, e.trial.status);
    out << ", \"dofs\": " << e.trial.dofs << ", \"simulated_s\": " << e.trial.simulatedSeconds
        << ", \"steps\": " << e.trial.steps << ", \"wall_per_simulated_s\": {\"median\": ";
    writeJsonNumber(out, e.medianCost());
    out << ", \"samples\": [";
    for (size_t i = 0; i < e.costs.size(); ++i) {
      out << (i ? ", " : "");
      writeJsonNumber(out, e.costs[i]);
    }
    out << "]}, \"step_us_median\": ";
    writeJsonNumber(out, e.medianStepUs());
    out << ", \"metrics\": {";
    bool firstMetric = true;
    for (const auto& [name, value] : e.trial.metrics) {
      out << (firstMetric ? "" : ", ") << '"' << name << "\": ";
      writeJsonNumber(out, value);
      firstMetric = false;
    }
    out << "}}";
    first = false;
  }
  out << "\n  ]\n}\n";
}

// gnuplot data: one block per (scene, engine), columns cost (wall s per simulated s), |error| in %,
// resolution; blocks separated by two blank lines so that `index` selects them (plot.gp).
void writePlotData(const std::string& path, const std::vector<Entry>& entries) {
  std::ofstream out(path);
  out << "# rope_compare: accuracy against cost. Blocks (gnuplot index): ";
  int block = 0;
  for (Scene scene : {Scene::kCatenary, Scene::kHeavyLoad}) {
    const char* name = scene == Scene::kCatenary ? "sag_error" : "strain_error";
    for (Engine engine : kEngines) {
      out << (block ? "\n\n" : "\n") << "# " << block << ": " << sceneName(scene) << ' ' << engineName(engine)
          << "\n# wall_s_per_simulated_s abs_error_percent resolution\n";
      bool any = false;
      for (const Entry& e : entries) {
        if (e.scene != scene || e.engine != engine || !e.trial.ok() || std::isnan(metric(e, name))) continue;
        if (metric(e, "load_mass_kg") > 0) continue;  // the load check is not part of the sweep
        out << e.medianCost() << ' ' << std::max(1e-3, 100 * std::abs(metric(e, name))) << ' ' << e.setting.resolution << '\n';
        any = true;
      }
      if (!any) out << "nan nan 0\n";  // keeps the block indices stable
      ++block;
    }
  }
}

// --try ENGINE SCENE RESOLUTION ITERATIONS SUBSTEPS STRETCH SECONDS: one trial, its metrics printed
// (for looking at one setting; engine and scene by the names used in the JSON).
int tryOne(char** args) {
  Engine engine = Engine::kSplineRope;
  for (Engine e : kEngines)
    if (std::strcmp(engineName(e), args[0]) == 0) engine = e;
  Scene scene = Scene::kCatenary;
  for (Scene s : {Scene::kCatenary, Scene::kHeavyLoad, Scene::kThinBar, Scene::kDrape, Scene::kScaling})
    if (std::strcmp(sceneName(s), args[1]) == 0) scene = s;
  Setting setting = res(std::atoi(args[2]), std::atoi(args[3]), std::atoi(args[4]), std::atoi(args[5]) != 0);
  Limits limits;
  limits.seconds = std::atof(args[6]);
  limits.wallBudget = 60;
  const Trial t = run(engine, scene, setting, limits);
  std::printf("%s %s %s: %s, %d dof, %.3f s simulated, %.4f wall s per simulated s, %.1f us per step\n", engineName(engine),
              sceneName(scene), setting.label().c_str(), t.status.c_str(), t.dofs, t.simulatedSeconds, t.costPerSecond(),
              t.stepMicroseconds());
  for (const auto& [name, value] : t.metrics) std::printf("  %s = %.6g\n", name.c_str(), value);
  return 0;
}

struct Options {
  bool quick = false;
  std::string out = "rope_compare";
  std::string checkReadme;  // --check: the README whose comparison claims the run must bear out
  int repeats = 3;
};

// Reads the command line into options. Returns the exit status when the program should stop here:
// after a --try run, or 2 for a bad argument.
std::optional<int> parseArguments(int argc, char** argv, Options& options) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") options.quick = true;
    else if (arg == "--out" && i + 1 < argc) options.out = argv[++i];
    else if (arg == "--repeats" && i + 1 < argc) options.repeats = std::max(1, std::atoi(argv[++i]));
    else if (arg == "--check" && i + 1 < argc) options.checkReadme = argv[++i];
    else if (arg == "--try" && i + 7 < argc) return tryOne(argv + i + 1);
    else {
      std::cerr << "usage: rope_compare [--quick] [--out PREFIX] [--repeats N] [--check README]\n";
      return 2;
    }
  }
  if (options.quick) options.repeats = 1;
  return std::nullopt;
}

// Wall seconds since the program started, for the progress lines.
class Clock {
 public:
  double elapsed() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// Everything the runs produced.
struct Results {
  std::vector<Entry> all;  // every trial, in the order of the JSON and the sweep table
  std::map<Scene, std::vector<Entry>> byScene;
  std::vector<Entry> loadCheck;  // each engine's heavy-load setting run again at half the load
  std::vector<int> sizes;        // rope sizes of the scaling scene
  int softIterations = 16;       // the soft body's iterations in the scaling scene
  double totalSeconds = 0.0;     // wall time of all the runs
  Limits heavyLimits;            // the heavy-load plan's limits
};

// The four scenes of the plan, each engine's settings in turn; on the full run the soft body's
// iteration count is also calibrated to the heavy load.
void runScenePlans(const Options& options, const Clock& clock, Results& results) {
  for (const Plan& plan : options.quick ? quickPlan() : fullPlan(15.0)) {
    std::fprintf(stderr, "[%6.1f s] %s\n", clock.elapsed(), sceneName(plan.scene));
    std::vector<Entry>& entries = results.byScene[plan.scene];
    entries = runPlan(plan, options.repeats);
    if (plan.scene == Scene::kHeavyLoad) {
      results.heavyLimits = plan.limits;
      if (!options.quick) {
        const std::vector<Entry> calibrated = calibrateSoftBody(entries, plan.limits, options.repeats);
        entries.insert(entries.end(), calibrated.begin(), calibrated.end());
      }
    }
    results.all.insert(results.all.end(), entries.begin(), entries.end());
  }
}

// Load check: each engine's cheapest setting within 1 % at 10 kg, run again with half the load.
void runLoadCheck(const Clock& clock, Results& results) {
  Limits half = results.heavyLimits;
  half.loadMass = 0.5 * HeavyLoadSpec{}.crane.boxMass;
  for (Engine e : kEngines)
    if (const Entry* best = cheapestWithin(results.byScene[Scene::kHeavyLoad], e, "strain_error")) {
      results.loadCheck.push_back(measure(e, Scene::kHeavyLoad, best->setting, half, 1));
      std::fprintf(stderr, "[%6.1f s] load check %s %s\n", clock.elapsed(), engineName(e), best->setting.label().c_str());
    }
}

// The hanging rope at growing sizes; the soft body runs with the iterations of its cheapest catenary
// setting within 1 %.
void runScalingScene(const Options& options, const Clock& clock, Results& results) {
  const Entry* softCatenary = cheapestWithin(results.byScene[Scene::kCatenary], Engine::kSoftBody, "sag_error");
  results.softIterations = softCatenary ? softCatenary->setting.iterations : 16;
  std::fprintf(stderr, "[%6.1f s] scaling\n", clock.elapsed());
  results.sizes = options.quick ? std::vector<int>{16, 64} : std::vector<int>{16, 64, 256, 1024};
  std::vector<Entry>& scaling = results.byScene[Scene::kScaling];
  scaling = runScaling(results.sizes, options.repeats, results.softIterations, options.quick ? 2.0 : 8.0);
  results.all.insert(results.all.end(), scaling.begin(), scaling.end());
}

Results runComparison(const Options& options) {
  const Clock clock;
  Results results;
  runScenePlans(options, clock, results);
  runLoadCheck(clock, results);
  runScalingScene(options, clock, results);
  for (Entry& e : results.loadCheck) e.trial.metrics["load_mass_kg"] = 0.5 * HeavyLoadSpec{}.crane.boxMass;
  results.all.insert(results.all.end(), results.loadCheck.begin(), results.loadCheck.end());
  results.totalSeconds = clock.elapsed();
  return results;
}

// The README's comparison table (markdown) and the same cells by key for the JSON summary.
class SummaryTable {
 public:
  SummaryTable() {
    markdown_ << "| scene (figure) | SplineRope | Bullet soft body (`CreateRope`) | MuJoCo " << mj_versionString()
              << " chain (`composite rope`) |\n|---|---|---|---|\n";
  }
  void row(const std::string& key, const std::string& title, const std::string& a, const std::string& b,
           const std::string& c) {
    markdown_ << "| " << title << " | " << a << " | " << b << " | " << c << " |\n";
    cells_[key + ".splinerope"] = a;
    cells_[key + ".bullet_softbody"] = b;
    cells_[key + ".mujoco_chain"] = c;
  }
  std::string markdown() const { return markdown_.str(); }
  const std::map<std::string, std::string>& cells() const { return cells_; }

 private:
  std::ostringstream markdown_;
  std::map<std::string, std::string> cells_;
};

// (1) and (2): the cheapest setting within 1 % and its cost against SplineRope's, and (2)'s setting
// at half the load.
void addAccuracyRows(SummaryTable& table, const Results& results) {
  const auto& cat = results.byScene.at(Scene::kCatenary);
  const auto& heavy = results.byScene.at(Scene::kHeavyLoad);
  table.row("catenary", "(1) catenary: cheapest setting with \\|sag error\\| ≤ 1 %: error, wall ms per simulated s",
            accuracyCell(cat, Engine::kSplineRope, "sag_error"), accuracyCell(cat, Engine::kSoftBody, "sag_error"),
            accuracyCell(cat, Engine::kMuJoCo, "sag_error"));
  table.row("catenary_ratio", "(1) cost at equal accuracy, peer ÷ SplineRope", "1×",
            ratioCell(cat, Engine::kSoftBody, "sag_error"), ratioCell(cat, Engine::kMuJoCo, "sag_error"));
  table.row("heavy_load",
            "(2) heavy load: cheapest setting with \\|strain error\\| ≤ 1 % vs W/(EA): error, wall ms per simulated s",
            accuracyCell(heavy, Engine::kSplineRope, "strain_error"),
            accuracyCell(heavy, Engine::kSoftBody, "strain_error"), accuracyCell(heavy, Engine::kMuJoCo, "strain_error"));
  table.row("heavy_load_ratio", "(2) cost at equal accuracy, peer ÷ SplineRope", "1×",
            ratioCell(heavy, Engine::kSoftBody, "strain_error"), ratioCell(heavy, Engine::kMuJoCo, "strain_error"));
  std::map<Engine, std::string> checkCells;
  for (const Entry& e : results.loadCheck)
    checkCells[e.engine] = e.setting.label() + ": " + (e.trial.ok() ? percent(metric(e, "strain_error")) : e.trial.status);
  for (Engine e : kEngines)
    if (checkCells[e].empty()) checkCells[e] = "no setting to check";
  table.row("heavy_load_5kg", "(2) that setting with a 5 kg load instead: strain error vs W/(EA)",
            checkCells[Engine::kSplineRope], checkCells[Engine::kSoftBody], checkCells[Engine::kMuJoCo]);
}

// (3) and (4): the thin bar held or not, and the penetration into a box.
void addContactRows(SummaryTable& table, const Results& results) {
  const double barTop = DrapeSpec::thinBar().drape.obstacleTop;
  const double radius = DrapeSpec::box().drape.rod.radius;
  const auto& bar = results.byScene.at(Scene::kThinBar);
  table.row("thin_bar", "(3) thin bar (2 mm), dropped from 1 m: held or fell through",
            thinBarCell(bar, Engine::kSplineRope, barTop), thinBarCell(bar, Engine::kSoftBody, barTop),
            thinBarCell(bar, Engine::kMuJoCo, barTop));
  const auto& drape = results.byScene.at(Scene::kDrape);
  table.row("drape", "(4) drape on a box: max / resting (last 0.5 s) penetration",
            drapeCell(drape, Engine::kSplineRope, radius), drapeCell(drape, Engine::kSoftBody, radius),
            drapeCell(drape, Engine::kMuJoCo, radius));
}

// (5): time per step of the hanging rope at each size, and the peers' ratios to SplineRope's.
void addScalingRows(SummaryTable& table, const Results& results) {
  const auto& scaling = results.byScene.at(Scene::kScaling);
  std::map<Engine, std::string> scalingCells;
  for (const Entry& e : scaling) {
    std::string& cell = scalingCells[e.engine];
    // A run that failed still timed its steps until then: show the time and how it ended.
    cell += (cell.empty() ? "" : " / ") + fmt(e.medianStepUs() < 100 ? "%.1f" : "%.0f", e.medianStepUs()) +
            (e.trial.ok() ? "" : " (" + e.trial.status + " at step " + std::to_string(e.trial.steps) + ")");
  }
  std::string sizeText;
  for (int n : results.sizes) sizeText += (sizeText.empty() ? "" : " / ") + std::to_string(n);
  table.row("scaling",
            "(5) hanging rope at " + sizeText + " nodes: µs per step" +
                (results.softIterations != 1
                     ? " (soft body at " + std::to_string(results.softIterations) + " iterations)"
                     : ""),
            scalingCells[Engine::kSplineRope], scalingCells[Engine::kSoftBody], scalingCells[Engine::kMuJoCo]);
  std::string softRatio, mujocoRatio;
  for (size_t i = 0; i + 2 < scaling.size(); i += 3) {
    softRatio += (softRatio.empty() ? "" : " / ") + fmt("%.1f×", scaling[i + 1].medianStepUs() / scaling[i].medianStepUs());
    mujocoRatio +=
        (mujocoRatio.empty() ? "" : " / ") + fmt("%.0f×", scaling[i + 2].medianStepUs() / scaling[i].medianStepUs());
  }
  table.row("scaling_ratio", "(5) time per step, peer ÷ SplineRope", "1×", softRatio, mujocoRatio);
}

SummaryTable summaryTable(const Results& results) {
  SummaryTable table;
  addAccuracyRows(table, results);
  addContactRows(table, results);
  addScalingRows(table, results);
  return table;
}

// Every trial: setting, status, the scene's accuracy figure and its cost.
std::string sweepTable(const Results& results) {
  const double barTop = DrapeSpec::thinBar().drape.obstacleTop;
  std::ostringstream sweep;
  sweep << "| scene | engine | setting | dof | status | accuracy | wall ms per simulated s (median) | µs per step |\n"
           "|---|---|---|---|---|---|---|---|\n";
  for (const Entry& e : results.all) {
    std::string accuracy;
    if (e.scene == Scene::kCatenary) accuracy = "sag error " + percent(metric(e, "sag_error"));
    else if (e.scene == Scene::kHeavyLoad) accuracy = "strain error " + percent(metric(e, "strain_error"));
    else if (e.scene == Scene::kThinBar) accuracy = thinBarOutcome(e, barTop);  // an exploded run did not hold
    else if (e.scene == Scene::kDrape)
      accuracy = "penetration max " + fmt("%.2f", 1e3 * metric(e, "max_penetration_m")) + " mm, resting " +
                 fmt("%.2f", 1e3 * metric(e, "resting_penetration_m")) + " mm";
    const std::string scene = std::string(sceneName(e.scene)) + (metric(e, "load_mass_kg") > 0 ? " (5 kg load)" : "");
    sweep << "| " << scene << " | " << engineName(e.engine) << " | " << e.setting.label() << " | " << e.trial.dofs
          << " | " << e.trial.status << " | " << accuracy << " | " << ms(e.medianCost()) << " | "
          << fmt("%.1f", e.medianStepUs()) << " |\n";
  }
  return sweep.str();
}

// PREFIX.md, PREFIX.json and PREFIX.dat, and the summary on stdout. False if PREFIX.md cannot be
// written (then nothing else is).
bool writeOutputs(const Options& options, const Results& results, const SummaryTable& summary) {
  char header[256];
  std::snprintf(header, sizeof header, "rope_compare%s: %d repeat(s), %.0f s wall in total\n\n",
                options.quick ? " --quick" : "", options.repeats, results.totalSeconds);
  const std::string& out = options.out;
  {
    std::ofstream table(out + ".md");
    table << header << summary.markdown() << "\nEvery setting:\n\n" << sweepTable(results);
    if (!table) {
      std::fprintf(stderr, "rope_compare: cannot write %s.md (does the directory exist?)\n", out.c_str());
      return false;
    }
  }
  writeJson(out + ".json", results.all, options.repeats, results.totalSeconds, options.quick, summary.cells());
  writePlotData(out + ".dat", results.all);
  std::cout << header << summary.markdown();
  std::fprintf(stderr, "wrote %s.json, %s.md, %s.dat\n", out.c_str(), out.c_str(), out.c_str());
  return true;
}

// The smoke check: SplineRope must run every scene and hold the thin bar.
bool smokeCheckPasses(const Results& results) {
  const double barTop = DrapeSpec::thinBar().drape.obstacleTop;
  bool ok = true;
  for (const Entry& e : results.all)
    if (e.engine == Engine::kSplineRope && !e.trial.ok()) {
      std::fprintf(stderr, "FAIL: SplineRope %s: %s\n", sceneName(e.scene), e.trial.status.c_str());
      ok = false;
    }
  for (const Entry& e : results.byScene.at(Scene::kThinBar))
    if (e.engine == Engine::kSplineRope && !(metric(e, "highest_m") > barTop - 0.1)) {
      std::fprintf(stderr, "FAIL: SplineRope fell through the thin bar\n");
      ok = false;
    }
  return ok;
}

// --check README: holds the run to the claims of the README's comparison table that the default
// tests guard (compare.smoke runs --quick --check):
//   (2) heavy load: for each engine, the setting the row names was run, its strain error against
//       W/(EA) is the row's figure within kClaimTolerance, and within the 1 % the row claims;
//   (2) with a 5 kg load: the same setting at half the load, its figure within kClaimTolerance;
//   (3) thin bar: every setting run has the outcome the row states for it ("held", "fell through",
//       "exploded"), and SplineRope holds the bar while no peer setting does.
// The table prints errors to 0.01 %; kClaimTolerance is three times that. All three engines are
// deterministic, so a figure moves only when an engine's code or a scene changes: then the check
// fails until the table is measured again (the full run) and the README updated.
constexpr double kClaimTolerance = 0.0003;
const char* const kComparisonHeading = "## Compared with Bullet soft-body and MuJoCo ropes";

class ClaimCheck {
 public:
  void pass(const std::string& text) { std::fprintf(stderr, "claim ok: %s\n", text.c_str()); }
  void fail(const std::string& text) {
    std::fprintf(stderr, "CLAIM FAILED: %s\n", text.c_str());
    ++failures_;
  }
  int failures() const { return failures_; }

 private:
  int failures_ = 0;
};

// The cells of the comparison section's table row whose title cell starts with `title` (title cell
// first), or none. Cells are separated by " | "; an escaped "\|" inside a cell has no space before it.
std::vector<std::string> readmeRow(const std::string& readme, const std::string& title) {
  std::istringstream lines(readme);
  std::string line;
  bool inSection = false;
  while (std::getline(lines, line)) {
    if (line.rfind("## ", 0) == 0) inSection = line == kComparisonHeading;
    if (!inSection || line.rfind("| " + title, 0) != 0) continue;
    std::string body = line.substr(2);
    if (body.size() >= 2 && body.compare(body.size() - 2, 2, " |") == 0) body.resize(body.size() - 2);
    std::vector<std::string> cells;
    for (size_t start = 0;;) {
      const size_t bar = body.find(" | ", start);
      cells.push_back(body.substr(start, bar == std::string::npos ? std::string::npos : bar - start));
      if (bar == std::string::npos) break;
      start = bar + 3;
    }
    return cells;
  }
  return {};
}

// A strain cell, "LABEL (N dof): -0.53 %, 1.67 ms" or "LABEL: -0.19 %": the setting's label and the
// error as a fraction. False if the cell is not of that form.
bool parseStrainCell(const std::string& cell, std::string& label, double& error) {
  const size_t colon = cell.find(": ");
  if (colon == std::string::npos || cell.rfind("**", 0) == 0) return false;
  label = cell.substr(0, std::min(colon, cell.find(" (")));
  const char* begin = cell.c_str() + colon + 2;
  char* end = nullptr;
  const double percent = std::strtod(begin, &end);
  if (end == begin || std::strncmp(end, " %", 2) != 0) return false;
  error = percent / 100;
  return true;
}

std::string engineTitle(Engine engine) {
  switch (engine) {
    case Engine::kSplineRope: return "SplineRope";
    case Engine::kSoftBody: return "soft body";
    case Engine::kMuJoCo: return "MuJoCo";
  }
  return "?";
}

// (2): the row titled `title`, each engine's stated setting and strain error against `entries`.
void checkStrainRow(const std::string& readme, const std::string& title, const std::string& claim,
                    const std::vector<Entry>& entries, bool withinTarget, ClaimCheck& check) {
  const std::vector<std::string> row = readmeRow(readme, title);
  if (row.size() != 1 + kEngines.size()) {
    check.fail(claim + ": no row \"" + title + "...\" with " + std::to_string(1 + kEngines.size()) +
               " cells in the README's comparison table");
    return;
  }
  for (size_t k = 0; k < kEngines.size(); ++k) {
    const Engine engine = kEngines[k];
    const std::string what = claim + ", " + engineTitle(engine);
    std::string label;
    double stated = kNaN;
    if (!parseStrainCell(row[k + 1], label, stated)) {
      check.fail(what + ": the README cell \"" + row[k + 1] + "\" states no setting and strain error to check");
      continue;
    }
    const auto found = std::find_if(entries.begin(), entries.end(), [&](const Entry& e) {
      return e.engine == engine && e.setting.label() == label;
    });
    if (found == entries.end()) {
      check.fail(what + ": the README states setting " + label + ", which this run did not make (quickPlan)");
      continue;
    }
    const std::string about = what + " " + label + ": strain error vs W/(EA) ";
    if (!found->trial.ok()) {
      check.fail(about + "not measured, the run " + found->trial.status + " (README: " + percent(stated) + ")");
      continue;
    }
    const double measured = metric(*found, "strain_error");
    const std::string text = about + fmt("%+.3f %%", 100 * measured) + ", README " + percent(stated) + " ± " +
                             fmt("%.2f %%", 100 * kClaimTolerance) + (withinTarget ? ", within 1 %" : "");
    if (!(std::abs(measured - stated) <= kClaimTolerance) || (withinTarget && !(std::abs(measured) <= kTargetError)))
      check.fail(text);
    else
      check.pass(text);
  }
}

// (3): every thin-bar trial has the outcome the README states for its setting; SplineRope held, the
// peers did not.
void checkThinBar(const std::string& readme, const std::vector<Entry>& entries, ClaimCheck& check) {
  const std::string title = "(3) thin bar";
  const std::vector<std::string> row = readmeRow(readme, title);
  if (row.size() != 1 + kEngines.size()) {
    check.fail("(3) thin bar: no row \"" + title + "...\" with 4 cells in the README's comparison table");
    return;
  }
  const double barTop = DrapeSpec::thinBar().drape.obstacleTop;
  for (size_t k = 0; k < kEngines.size(); ++k) {
    const Engine engine = kEngines[k];
    std::map<std::string, std::string> stated;  // setting label -> outcome
    for (size_t start = 0;;) {
      const size_t end = row[k + 1].find("; ", start);
      const std::string item = row[k + 1].substr(start, end == std::string::npos ? std::string::npos : end - start);
      const size_t colon = item.find(": ");
      if (colon != std::string::npos) stated[item.substr(0, colon)] = item.substr(colon + 2);
      if (end == std::string::npos) break;
      start = end + 2;
    }
    int checked = 0;
    for (const Entry& e : entries) {
      if (e.engine != engine) continue;
      ++checked;
      const std::string outcome = thinBarOutcome(e, barTop);
      std::string what = "(3) thin bar, " + engineTitle(engine) + " " + e.setting.label() + ": " + outcome;
      if (e.trial.ok()) what += fmt(" (highest point at the end %.3f m", metric(e, "highest_m")) + fmt(", bar top %.3f m)", barTop);
      else what += fmt(" after %.3f s", e.trial.simulatedSeconds);
      const auto it = stated.find(e.setting.label());
      if (it == stated.end()) check.fail(what + "; the README states nothing for this setting");
      else if (outcome != it->second) check.fail(what + "; the README states \"" + it->second + "\"");
      else if ((engine == Engine::kSplineRope) != (outcome == "held"))
        check.fail(what + "; the claim is that SplineRope holds the bar and no peer does");
      else check.pass(what + ", as the README states");
    }
    if (checked == 0) check.fail("(3) thin bar, " + engineTitle(engine) + ": this run made no thin-bar trial");
  }
}

// Exit status of --check: 0 when every claim holds, 1 otherwise (each failure named on stderr).
int checkClaims(const std::string& readmePath, const Results& results) {
  std::ifstream in(readmePath);
  std::stringstream text;
  text << in.rdbuf();
  const std::string readme = text.str();
  if (!in || readme.find(kComparisonHeading) == std::string::npos) {
    std::fprintf(stderr, "CLAIM FAILED: cannot read the section \"%s\" of %s\n", kComparisonHeading + 3,
                 readmePath.c_str());
    return 1;
  }
  ClaimCheck check;
  checkStrainRow(readme, "(2) heavy load:", "(2) heavy load", results.byScene.at(Scene::kHeavyLoad), true, check);
  checkStrainRow(readme, "(2) that setting with a 5 kg load", "(2) with a 5 kg load", results.loadCheck, false, check);
  checkThinBar(readme, results.byScene.at(Scene::kThinBar), check);
  std::fprintf(stderr, "%s: %d claim(s) of %s failed\n", check.failures() ? "FAIL" : "ok", check.failures(),
               readmePath.c_str());
  return check.failures() ? 1 : 0;
}

int main(int argc, char** argv) {
  Options options;
  if (const std::optional<int> exitStatus = parseArguments(argc, argv, options)) return *exitStatus;
  const Results results = runComparison(options);
  if (!writeOutputs(options, results, summaryTable(results))) return 1;
  const bool smokeOk = smokeCheckPasses(results);
  const bool claimsOk = options.checkReadme.empty() || checkClaims(options.checkReadme, results) == 0;
  return smokeOk && claimsOk ? 0 : 1;
}

}  // namespace
}  // namespace rope::compare

int main(int argc, char** argv) { return rope::compare::main(argc, argv); }
