// SPDX-License-Identifier: MIT
// Malformed and invalid scene files, run through the real command line (`ropesim run`): each stops
// before simulating with exit status 2 and a message naming the JSON path and the value.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace {

struct Outcome {
  int status = -1;
  std::string out, err;
};

std::string read(const std::string& file) {
  std::ifstream stream(file);
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

// ctest runs the cases side by side: each process has its own files, and removes them when it ends
// (every case is a process of its own: a CI machine gathered some 60 files per run otherwise).
class ScratchFiles {
 public:
  ~ScratchFiles() {
    std::error_code ignored;
    for (const std::string& path : paths_) std::filesystem::remove_all(path, ignored);
  }
  std::string path(const std::string& name) {
    const std::string path = testing::TempDir() + "/scene_file_cli_" + std::to_string(getpid()) + "_" + name;
    paths_.insert(path);
    return path;
  }

 private:
  std::set<std::string> paths_;
};

std::string scratch(const std::string& name) {
  static ScratchFiles files;
  return files.path(name);
}

Outcome ropesim(const std::string& arguments) {
  const std::string command = std::string(SPLINEROPE_ROPESIM) + " " + arguments + " --no-render --quiet > " +
                              scratch("out.txt") + " 2> " + scratch("err.txt");
  const int raw = std::system(command.c_str());
  Outcome run;
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  run.out = read(scratch("out.txt"));
  run.err = read(scratch("err.txt"));
  return run;
}

std::string writeScene(const std::string& text) {
  const std::string file = scratch("scene.json");
  std::ofstream(file) << text;
  return file;
}

// A valid scene the cases below break one thing of.
const char* kBody = R"({"name": "box", "shape": "box", "halfExtents": [0.1, 0.1, 0.1]})";
const char* kRope = R"({"name": "rope", "shape": {"type": "segment", "from": [0, 1, 0], "to": [1, 1, 0]}})";

std::string scene(const std::string& bodies, const std::string& ropes, const std::string& rest = "") {
  return "{\"bodies\": [" + bodies + "], \"ropes\": [" + ropes + "]" + rest + "}";
}

struct BadFile {
  const char* kind;
  std::string text;
  std::string message;  // what stderr must contain: the path and the value or reason
};

class BadSceneFile : public testing::TestWithParam<BadFile> {};

TEST_P(BadSceneFile, ExitsWithTwoAndNamesThePath) {
  const BadFile& bad = GetParam();
  const Outcome run = ropesim("run " + writeScene(bad.text) + " --seconds 0.01");
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_NE(run.err.find(bad.message), std::string::npos) << "stderr: " << run.err;
  EXPECT_EQ(run.out, "") << "nothing was simulated";
}

const std::string kRopeWith = R"({"name": "rope", "shape": {"type": "segment", "from": [0, 1, 0], "to": [1, 1, 0]}, )";

INSTANTIATE_TEST_SUITE_P(
    Kinds, BadSceneFile,
    testing::Values(
        BadFile{"not JSON", "{\"bodies\": [", "not valid JSON"},
        BadFile{"not an object", "[1, 2]", "scene file: [1,2], must be an object, not array"},
        BadFile{"unknown top-level key", "{\"gravty\": [0, -9.81, 0]}", "gravty: unknown key (did you mean 'gravity'?)"},
        BadFile{"wrong type", "{\"timeStep\": \"fast\"}", "timeStep: \"fast\", must be a number, not string"},
        BadFile{"NaN written as a string", scene(kBody, kRopeWith + R"("settings": {"radius": "NaN"}})"),
                "ropes[0].settings.radius: \"NaN\", must be a number"},
        BadFile{"negative rope radius", scene(kBody, kRopeWith + R"("settings": {"radius": -0.01}})"),
                "ropes[0].settings.radius: -0.01, must be > 0"},
        BadFile{"negative box size", scene(R"({"name": "box", "shape": "box", "halfExtents": [0.1, -0.1, 0.1]})", kRope),
                "bodies[0].halfExtents[1]: -0.1, must be > 0"},
        BadFile{"missing body shape", scene(R"({"name": "box"})", kRope), "bodies[0].shape: missing (required)"},
        BadFile{"missing rope name", scene(kBody, R"({"shape": {"type": "segment", "from": [0, 1, 0], "to": [1, 1, 0]}})"),
                "ropes[0].name: missing (required)"},
        BadFile{"unknown shape", scene(R"({"name": "box", "shape": "cone"})", kRope),
                "bodies[0].shape: \"cone\", must be one of \"box\", \"sphere\", \"capsule\", \"cylinder\", \"plane\""},
        BadFile{"attachment to a body that does not exist",
                scene(kBody, kRopeWith + R"("attachments": [{"s": "end", "body": "clip"}]})"),
                "ropes[0].attachments[0].body: \"clip\", no body of that name"},
        BadFile{"check on a rope that does not exist",
                scene(kBody, kRope, R"(, "checks": [{"name": "c", "type": "penetration", "rope": "cable", "max": 0.001}])"),
                "checks[0].rope: \"cable\", no rope of that name"},
        BadFile{"two bodies of one name", scene(std::string(kBody) + ", " + kBody, kRope),
                "bodies[1].name: \"box\", another body has this name"},
        BadFile{"dynamic body without a mass", scene(R"({"name": "b", "shape": "sphere", "radius": 0.1, "motion": "dynamic"})", kRope),
                "bodies[0].mass: missing (required)"},
        BadFile{"static body with a mass", scene(R"({"name": "b", "shape": "sphere", "radius": 0.1, "mass": 1})", kRope),
                "bodies[0].mass: 1, only a dynamic body has a mass"},
        BadFile{"vector of two", "{\"gravity\": [0, -9.81]}", "gravity: [0,-9.81], must be an array of 3 numbers [x, y, z]"},
        BadFile{"fraction where a count goes", scene(kBody, kRopeWith + R"("settings": {"initialControlPoints": 3.5}})"),
                "ropes[0].settings.initialControlPoints: 3.5, must be a whole number"},
        BadFile{"range the library rejects", scene(kBody, kRopeWith + R"("settings": {"insertAngle": 3.0, "removeAngle": 2.0}})"),
                "ropes[0].settings.removeAngle: 2.0, must satisfy settings.insertAngle < removeAngle < pi"},
        BadFile{"misspelt settings key", scene(kBody, kRopeWith + R"("settings": {"youngModulus": 1e8}})"),
                "ropes[0].settings.youngModulus: unknown key (did you mean 'youngsModulus'?)"},
        BadFile{"pin beyond the rope", scene(kBody, kRopeWith + R"("pins": [{"s": 5}]})"), "ropes[0].pins[0].s: 5"},
        BadFile{"segment of zero length", scene(kBody, R"({"name": "rope", "shape": {"type": "segment", "from": [0, 1, 0], "to": [0, 1, 0]}})"),
                "ropes[0].shape.to: [0,1,0], must differ from 'from'"},
        BadFile{"bounds the wrong way round",
                scene(kBody, kRope, R"(, "checks": [{"name": "t", "type": "tension", "rope": "rope", "s": 0.5, "min": 5, "max": 1}])"),
                "checks[0].max: 1, must be >= 'min'"},
        BadFile{"check without a type", scene(kBody, kRope, R"(, "checks": [{"name": "t", "rope": "rope"}])"),
                "checks[0].type: missing (required)"},
        BadFile{"cut of a rope that does not exist",
                scene(kBody, kRope, R"(, "events": [{"type": "cut", "time": 1, "rope": "cable", "s": 0.5, "name": "piece"}])"),
                "events[0].rope: \"cable\", no rope of that name"},
        BadFile{"keyframes out of order",
                scene(R"({"name": "k", "shape": "sphere", "radius": 0.1, "motion": "kinematic", "keyframes": [{"time": 1, "position": [0, 0, 0]}, {"time": 0.5, "position": [1, 0, 0]}]})", kRope),
                "bodies[0].keyframes[1].time: 0.5, must be later than the keyframe before"},
        BadFile{"rotation that is not a unit quaternion",
                scene(R"({"name": "b", "shape": "box", "halfExtents": [1, 1, 1], "rotation": [0, 0, 0, 2]})", kRope),
                "bodies[0].rotation: [0,0,0,2], must be a unit quaternion"},
        BadFile{"keyframes on a static body",
                scene(R"({"name": "b", "shape": "sphere", "radius": 0.1, "keyframes": [{"time": 0, "position": [0, 0, 0]}]})", kRope),
                "bodies[0].keyframes: does not apply to a static body"},
        BadFile{"camera looking along its up vector", "{\"camera\": {\"eye\": [0, 5, 0], \"target\": [0, 0, 0]}}", "camera.up"},
        BadFile{"key of another shape", scene(R"({"name": "b", "shape": "box", "halfExtents": [1, 1, 1], "radius": 0.5})", kRope),
                "bodies[0].radius: does not apply to a box"},
        BadFile{"tension check at two places",
                scene(kBody, kRope, R"(, "checks": [{"name": "t", "type": "tension", "rope": "rope", "s": 0.5, "winch": "end", "max": 1}])"),
                "checks[0]: a tension check needs exactly one of 's', 'attachment', 'winch'"},
        BadFile{"two checks of one name",
                scene(kBody, kRope, R"(, "checks": [{"name": "h", "type": "health"}, {"name": "h", "type": "health"}])"),
                "checks[1].name: \"h\", another check has this name"},
        BadFile{"attachment spring the library rejects",
                scene(kBody, kRopeWith + R"("attachments": [{"s": "end", "body": "box", "stiffness": -5}]})"),
                "ropes[0].attachments[0].stiffness: -5, must be > 0"},
        BadFile{"text where a flag goes", scene(kBody, kRopeWith + R"("settings": {"selfContact": "yes"}})"),
                "ropes[0].settings.selfContact: \"yes\", must be true or false"},
        BadFile{"moving plane", scene(R"({"name": "p", "shape": "plane", "motion": "kinematic"})", kRope),
                "bodies[0].motion: \"kinematic\", a plane must be static"},
        BadFile{"distributed force the wrong way along the rope",
                scene(kBody, kRope, R"(, "events": [{"type": "distributedForce", "time": 0, "until": 1, "rope": "rope", "s0": 0.6, "s1": 0.2, "forcePerLength": [1, 0, 0]}])"),
                "events[0].s1: 0.2, must give s1 > s0"},
        BadFile{"distributed force beyond the rope's end",
                scene(kBody, kRope, R"(, "events": [{"type": "distributedForce", "time": 0, "until": 1, "rope": "rope", "s1": 5, "forcePerLength": [1, 0, 0]}])"),
                "events[0].s1: 5, must be on the rope"},
        BadFile{"distributed force without a force per length",
                scene(kBody, kRope, R"(, "events": [{"type": "distributedForce", "time": 0, "until": 1, "rope": "rope"}])"),
                "events[0].forcePerLength: missing (required)"},
        BadFile{"force per length on a point force",
                scene(kBody, kRope, R"(, "events": [{"type": "force", "time": 0, "until": 1, "rope": "rope", "s": 0.5, "force": [1, 0, 0], "forcePerLength": [1, 0, 0]}])"),
                "events[0].forcePerLength: does not apply to a force event"},
        BadFile{"cylinder along an axis that is not one",
                scene(R"({"name": "c", "shape": "cylinder", "halfExtents": [0.1, 0.1, 0.2], "axis": "w"})", kRope),
                "bodies[0].axis: \"w\", must be one of \"x\", \"y\", \"z\""},
        BadFile{"axis of a box", scene(R"({"name": "b", "shape": "box", "halfExtents": [1, 1, 1], "axis": "z"})", kRope),
                "bodies[0].axis: does not apply to a box"},
        BadFile{"own gravity of a static body",
                scene(R"({"name": "b", "shape": "sphere", "radius": 0.1, "gravity": [0, -1, 0]})", kRope),
                "bodies[0].gravity: does not apply to a static body"},
        BadFile{"gravity ramp without a gravity",
                scene(R"({"name": "b", "shape": "sphere", "radius": 0.1, "motion": "dynamic", "mass": 1, "gravityRampTime": 0.2})", kRope),
                "bodies[0].gravityRampTime: 0.2, needs the body's own 'gravity'"},
        BadFile{"negative gravity ramp",
                scene(R"({"name": "b", "shape": "sphere", "radius": 0.1, "motion": "dynamic", "mass": 1, "gravity": [1, 0, 0], "gravityRampTime": -1})", kRope),
                "bodies[0].gravityRampTime: -1, must be >= 0"},
        BadFile{"keyframe interpolation that is not one",
                scene(R"({"name": "k", "shape": "sphere", "radius": 0.1, "motion": "kinematic", "keyframes": [{"time": 0, "position": [0, 0, 0], "interpolation": "cubic"}]})", kRope),
                "bodies[0].keyframes[0].interpolation: \"cubic\", must be one of \"linear\", \"smoothstep\""},
        BadFile{"release of an attachment the rope does not have",
                scene(kBody, kRope, R"(, "events": [{"type": "release", "time": 1, "rope": "rope", "attachment": "hook"}])"),
                "events[0].attachment: \"hook\", the rope has no pin or attachment of that name"}),
    [](const testing::TestParamInfo<BadFile>& info) {
      std::string name;
      for (const char c : std::string(info.param.kind)) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
      return name;
    });

// Meshes are read with the scene file, relative to its directory: a missing, empty or broken OBJ
// stops before simulating.
TEST(BadSceneFile, Meshes) {
  const std::string empty = scratch("empty.obj"), broken = scratch("broken.obj"), cube = scratch("cube.obj");
  std::ofstream(empty) << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  std::ofstream(broken) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n";
  std::ofstream(cube) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n";
  const auto name = [](const std::string& path) { return path.substr(path.find_last_of('/') + 1); };
  const struct {
    std::string body, message;
  } cases[] = {
      {R"({"name": "clip", "shape": "mesh", "mesh": "nowhere.obj"})", "bodies[0].mesh: \"nowhere.obj\", not found"},
      {R"({"name": "clip", "shape": "mesh", "mesh": ")" + name(empty) + R"("})", "bodies[0].mesh: \"" + name(empty) + "\", has no triangles"},
      {R"({"name": "clip", "shape": "mesh", "mesh": ")" + name(broken) + R"("})",
       "bodies[0].mesh: \"" + name(broken) + "\", line 4: face index 7 with 3 vertices so far"},
      {R"({"name": "clip", "shape": "mesh", "mesh": ")" + name(cube) + R"(", "meshType": "triangleMesh", "motion": "dynamic", "mass": 1})",
       "bodies[0].meshType: \"triangleMesh\", a triangle mesh must be static"},
      {R"({"name": "clip", "shape": "mesh", "mesh": ")" + name(cube) + R"(", "scale": 0})", "bodies[0].scale: 0, must be > 0"},
      {R"({"name": "clip", "shape": "box", "halfExtents": [1, 1, 1], "mesh": ")" + name(cube) + R"("})",
       "bodies[0].mesh: does not apply to a box"},
  };
  for (const auto& bad : cases) {
    SCOPED_TRACE(bad.body);
    const Outcome run = ropesim("run " + writeScene(scene(bad.body, kRope)));
    EXPECT_EQ(run.status, 2) << run.err;
    EXPECT_NE(run.err.find(bad.message), std::string::npos) << run.err;
  }
  // The same cube as a convex hull is fine.
  const Outcome good = ropesim("run " + writeScene(scene(R"({"name": "clip", "shape": "mesh", "mesh": ")" + name(cube) + R"("})", kRope)) +
                               " --seconds 0.01");
  EXPECT_EQ(good.status, 0) << good.err;
}

// A .bullet file that is missing or is not one stops before simulating.
TEST(BadSceneFile, BulletFiles) {
  const std::string fake = scratch("fake.bullet");
  std::ofstream(fake) << "this is not a Bullet file\n";
  const std::string fakeName = fake.substr(fake.find_last_of('/') + 1);
  const struct {
    std::string body, message;
  } cases[] = {
      {R"({"name": "cell", "shape": "bulletFile", "file": "nowhere.bullet"})", "bodies[0].file: \"nowhere.bullet\", not found"},
      {R"({"name": "cell", "shape": "bulletFile", "file": ")" + fakeName + R"("})",
       "bodies[0].file: \"" + fakeName + "\", not a .bullet file (no BULLET header)"},
      {R"({"name": "cell", "shape": "bulletFile", "file": ")" + fakeName + R"(", "mass": 2})",
       "bodies[0].mass: does not apply to a bulletFile"},
  };
  for (const auto& bad : cases) {
    SCOPED_TRACE(bad.body);
    const Outcome run = ropesim("run " + writeScene(scene(bad.body, kRope)));
    EXPECT_EQ(run.status, 2) << run.err;
    EXPECT_NE(run.err.find(bad.message), std::string::npos) << run.err;
  }
}

TEST(BadSceneFile, MissingFile) {
  const Outcome run = ropesim("run /nonexistent/scene.json");
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("cannot open '/nonexistent/scene.json'"), std::string::npos) << run.err;
}

TEST(BadSceneFile, OverrideOfAPathThatIsNotThere) {
  const Outcome run = ropesim("run " + writeScene(scene(kBody, kRope)) + " --set ropes[3].settings.radius=0.01");
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("--set ropes[3].settings.radius: 'ropes' has no element [3]"), std::string::npos) << run.err;
}

TEST(BadSceneFile, OverrideWithAnInvalidValueNamesTheKey) {
  const Outcome run = ropesim("run " + writeScene(scene(kBody, kRope)) + " --set ropes[0].settings.youngsModulus=-1");
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("ropes[0].settings.youngsModulus: -1, must be > 0"), std::string::npos) << run.err;
}

TEST(SceneFileVerdict, ExitStatusIsZeroWhenEveryCheckHoldsAndOneWhenOneFails) {
  const std::string checks = R"(, "duration": 0.2, "checks": [{"name": "ball falls", "type": "position", "body": "ball",
      "at": 0.2, "box": {"min": [-1, -1, -1], "max": [1, 0, 1]}}]})";
  const std::string ball = R"({"bodies": [{"name": "ball", "shape": "sphere", "radius": 0.1, "motion": "dynamic", "mass": 1, "position": [0, 0.1, 0]}])";
  const Outcome holds = ropesim("run " + writeScene(ball + checks));
  EXPECT_EQ(holds.status, 0) << holds.out << holds.err;
  EXPECT_NE(holds.out.find("1 checks, 0 failed"), std::string::npos) << holds.out;
  // The same file with the ball raised above the box by an override: the check fails.
  const Outcome fails = ropesim("run " + writeScene(ball + checks) + " --set bodies[0].position=[0,2,0]");
  EXPECT_EQ(fails.status, 1) << fails.out << fails.err;
  EXPECT_NE(fails.out.find("FAILS"), std::string::npos) << fails.out;
}

TEST(SceneFileVerdict, SnapshotOfTheFirstFailure) {
  const std::string dir = scratch("snapshots");
  const std::string file = writeScene(R"({"duration": 0.2, "camera": {"eye": [1, 1, 2], "target": [0, 0, 0]},
      "bodies": [{"name": "ball", "shape": "sphere", "radius": 0.1, "motion": "dynamic", "mass": 1}],
      "checks": [{"name": "ball stays up", "type": "position", "body": "ball", "target": [0, 0, 0], "max": 0.05},
                 {"name": "ball falls", "type": "position", "body": "ball", "at": 0.2, "box": {"min": [-1, -1, -1], "max": [1, 0, 1]}}]})");
  const Outcome run = ropesim("run " + file + " --size 64x48 --snapshot-on-failure " + dir);
  EXPECT_EQ(run.status, 1) << run.out << run.err;
  // Only the failed check has a picture; it failed when the ball had fallen 5 cm (0.1 s).
  const std::string png = read(dir + "/00_ball_stays_up.png");
  ASSERT_GT(png.size(), 8u) << run.out;
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_EQ(read(dir + "/01_ball_falls.png"), "");
  EXPECT_NE(run.out.find("snapshot of its first failure (t = 0.1 s): " + dir + "/00_ball_stays_up.png"), std::string::npos)
      << run.out;
}

}  // namespace
