// SPDX-License-Identifier: MIT
#include "demos/scenes/capstan_scene.h"
#include "demos/scenes/crane_scene.h"
#include "demos/scenes/cut_scene.h"
#include "demos/scenes/demo_scene.h"
#include "demos/scenes/drape_scene.h"
#include "demos/scenes/floor_pull_scene.h"
#include "demos/scenes/hang_scene.h"
#include "demos/scenes/knot_scene.h"
#include "demos/scenes/pile_scene.h"
#include "demos/scenes/resting_rope_scene.h"
#include "demos/scenes/sweep_scene.h"
#include "demos/scenes/tractrix_scene.h"
#include "demos/scenes/winch_scene.h"

namespace rope::demos {

namespace {

CapstanSceneSettings capstanDemoSettings() {
  CapstanSceneSettings settings;
  settings.loadRatio = 2.0;
  return settings;
}

}  // namespace

const std::vector<SceneEntry>& sceneCatalogue() {
  static const std::vector<SceneEntry> catalogue = {
      {"knot",
       "knot tying in a Bullet world: a loose overhand knot pulled tight by two grippers (self-contact)",
       10.0, [] { return std::unique_ptr<DemoScene>(new KnotScene(KnotSceneSettings{})); }},
      {"hang",
       "catenary: a 1.25 m rope whose pinned ends are drawn together to 1 m and left to settle",
       10.0, [] { return std::unique_ptr<DemoScene>(new HangScene(HangSceneSettings{})); }},
      {"pile", "Bullet world: a 2 m rope dropped as a loose coil from 0.5 m piles up on the ground (self-contact)",
       6.0, [] { return std::unique_ptr<DemoScene>(new PileScene(PileSceneSettings{})); }},
      {"sweep", "Bullet world: a kinematic tractrix hose dragged in a circle through a field of boxes, pushing them aside",
       6.0, [] { return std::unique_ptr<DemoScene>(new SweepScene(SweepSceneSettings{})); }},
      {"tractrix",
       "follow-the-leader: TRX with 20 segments beside TRX_SD_MRG on the same path",
       10.0, [] { return std::unique_ptr<DemoScene>(new TractrixScene(TractrixSceneSettings{})); }},
      {"drape", "Bullet world: a rope falls onto a static box and comes to rest on it",
       5.0, [] { return std::unique_ptr<DemoScene>(new DrapeScene(DrapeSceneSettings{})); }},
      {"thinbar", "Bullet world: a rope dropped from 1 m drapes over a 2 mm static bar",
       5.0, [] { return std::unique_ptr<DemoScene>(new DrapeScene(DrapeSceneSettings::thinBar())); }},
      {"crane", "Bullet world: a 10 kg box on a 0.01 kg/m rope, attached at both ends; the top is lifted",
       8.0, [] { return std::unique_ptr<DemoScene>(new CraneScene(CraneSceneSettings{})); }},
      {"winch",
       "Bullet world: a crane's winch lowers a 10 kg box by 0.5 m at 0.1 m/s and lifts it back (winch tension in --stats)",
       14.0, [] { return std::unique_ptr<DemoScene>(new WinchScene(WinchSceneSettings{})); }},
      {"cut", "Bullet world: a box swinging on a rope; the rope is cut at 1 s, the box falls, the top piece swings on",
       3.0, [] { return std::unique_ptr<DemoScene>(new CutScene(CutSceneSettings{})); }},
      {"capstan",
       "Bullet world: a rope over a 5 cm cylinder, wrapped by half a turn, mu 0.3, loads 10 N and 5 N (ratio 2, "
       "below exp(0.3 pi) = 2.57: it should hold)",
       3.0, [] { return std::unique_ptr<DemoScene>(new CapstanScene(capstanDemoSettings())); }},
      {"floorpull",
       "Bullet world: a rope on a box pulled along it by a distributed 6 N/kg against friction 0.5 (Coulomb: 1.095 m/s after 1 s)",
       1.5, [] { return std::unique_ptr<DemoScene>(new FloorPullScene(FloorPullSceneSettings{})); }},
      {"rest", "Bullet world: a straight rope lying at rest on a box (default settings)",
       2.0, [] { return std::unique_ptr<DemoScene>(new RestingRopeScene(RestingRopeSceneSettings{})); }},
  };
  return catalogue;
}

const SceneEntry* findScene(const std::string& name) {
  for (const SceneEntry& entry : sceneCatalogue()) {
    if (entry.name == name) return &entry;
  }
  return nullptr;
}

}  // namespace rope::demos
