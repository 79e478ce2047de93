// --scene end to end (docs/scene.md): the README's scene walk-through on the embedded xArm
// (a move into the box refused before anything moves, a move onto it planned with its
// clearance), a program line through the table refused with its file and line, a bad
// scene file refused with the key before the device opens; and `armctl sim xarm --scene`:
// a move into a box only the simulator knows stalls there and the host names the joint.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "run_armctl.hpp"

namespace {

using armctl::cli_test::contains;
using armctl::cli_test::run_armctl;

const std::string kScene = std::string(ARMCTL_SOURCE_DIR) + "/examples/scenes/xarm-desk.json";

std::filesystem::path temp_dir() {
  auto d = std::filesystem::temp_directory_path() / ("armctl-scene-cli-" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

void write(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }

TEST(SceneCli, AMoveIntoTheBoxIsRefusedAndOneOnTopOfItIsPlanned) {
  auto into = run_armctl("arm --arm xarm --scene " + kScene + " move-to x=150 y=-100 z=60");
  EXPECT_EQ(into.status, 1) << into.out;
  EXPECT_TRUE(contains(into.out, "would collide")) << into.out;
  EXPECT_TRUE(contains(into.out, "with box 'box'")) << into.out;
  EXPECT_FALSE(contains(into.out, "moving")) << into.out;
  // The same target without the scene moves.
  auto bare = run_armctl("arm --arm xarm move-to x=150 y=-100 z=60");
  EXPECT_EQ(bare.status, 0) << bare.out;

  auto beside = run_armctl("arm --arm xarm --scene " + kScene + " --json move-to x=150 y=-100 z=130", "2>/dev/null");
  ASSERT_EQ(beside.status, 0) << beside.out;
  const auto planned = nlohmann::json::parse(beside.out.substr(0, beside.out.find('\n')));
  EXPECT_EQ(planned.at("event"), "planned");
  EXPECT_GT(planned.at("clearance_mm").get<double>(), 0.0);
  EXPECT_LE(planned.at("clearance_mm").get<double>(), 50.0);
}

TEST(SceneCli, BehindTheBoxIsRefusedDirectAndPlannedAroundWithAvoid) {
  const std::string behind = "arm --arm xarm --scene " + kScene + " move-to x=150 y=-190 z=40";
  auto direct = run_armctl(behind);
  EXPECT_EQ(direct.status, 1) << direct.out;
  EXPECT_TRUE(contains(direct.out, "with box 'box'")) << direct.out;

  auto around = run_armctl(behind + " --avoid --wait");
  ASSERT_EQ(around.status, 0) << around.out;
  EXPECT_TRUE(contains(around.out, "around obstacles: ")) << around.out;
  EXPECT_TRUE(contains(around.out, " waypoints, planned in ")) << around.out;
  EXPECT_TRUE(contains(around.out, "no collision: smallest clearance")) << around.out;
  EXPECT_TRUE(contains(around.out, "position error: 0.")) << around.out;

  auto json_run = run_armctl("arm --arm xarm --scene " + kScene + " --json move-to x=150 y=-190 z=40 --avoid --avoid-time 2s",
                             "2>/dev/null");
  ASSERT_EQ(json_run.status, 0) << json_run.out;
  const auto planned = nlohmann::json::parse(json_run.out.substr(0, json_run.out.find('\n')));
  EXPECT_EQ(planned.at("event"), "planned");
  EXPECT_GE(planned.at("avoided").at("waypoints").get<int>(), 1);
  EXPECT_GT(planned.at("avoided").at("planning_s").get<double>(), 0.0);
  EXPECT_LT(planned.at("avoided").at("planning_s").get<double>(), 2.0);

  auto bad = run_armctl(behind + " --avoid --avoid-time 2h");
  EXPECT_EQ(bad.status, 1) << bad.out;
  auto linear = run_armctl(behind + " --avoid --linear");
  EXPECT_EQ(linear.status, 1) << linear.out;
  EXPECT_TRUE(contains(linear.out, "--avoid is not allowed with --linear")) << linear.out;
}

// A fence of x -300..150 mm and reduced mode (off) with servo1 narrowed to -90..90 deg, set by
// what `given` names (--arm, --scene): shown, a move out of the fence refused before anything
// moves and allowed with the fence off, a joint move beyond the range refused with reduced
// mode on.
void expect_the_fence_and_reduced_mode_hold(const std::string& given) {
  auto shown = run_armctl("arm " + given + " limits");
  ASSERT_EQ(shown.status, 0) << shown.out;
  EXPECT_TRUE(contains(shown.out, "fence: on: the tool point within x -300.0..150.0")) << shown.out;
  EXPECT_TRUE(contains(shown.out, "reduced mode: off")) << shown.out;
  auto out = run_armctl("arm " + given + " move-to x=200 y=0 z=150");
  EXPECT_EQ(out.status, 1) << out.out;
  EXPECT_TRUE(contains(out.out, "would leave the fence")) << out.out;
  EXPECT_FALSE(contains(out.out, "moving")) << out.out;
  auto off = run_armctl("arm " + given + " --fence off move-to x=200 y=0 z=150");
  EXPECT_EQ(off.status, 0) << off.out;
  auto reduced = run_armctl("arm " + given + " --reduced-mode on --fence off move-joints servo1=100deg");
  EXPECT_EQ(reduced.status, 1) << reduced.out;
  EXPECT_TRUE(contains(reduced.out, "joint 'servo1' beyond its reduced range")) << reduced.out;
}

// The fence and reduced mode from the CLI (docs/scene.md "Fence and reduced mode"): shown by
// `armctl arm limits`, a move out of the fence refused until `--fence off`, reduced mode
// switched on by `--reduced-mode on` refusing a joint move beyond its range, and a switch
// the scene does not set refused.
TEST(SceneCli, TheFenceAndReducedModeAreShownCheckedAndSwitched) {
  const auto dir = temp_dir();
  const std::string file = (dir / "fenced.json").string();
  write(file, R"({"fence": {"min": [-300, -300, 0], "max": [150, 300, 450]},
      "reduced": {"tool_speed": 50, "joints": {"servo1": [-90, 90]}, "on": false}})");
  expect_the_fence_and_reduced_mode_hold("--arm xarm --scene " + file);
  auto shown = run_armctl("arm --arm xarm --scene " + file + " limits");
  EXPECT_TRUE(contains(shown.out, "reduced mode: off: tool speed up to 50.0 mm/s; servo1 -90..90 deg")) << shown.out;
  auto json_shown = run_armctl("arm --arm xarm --scene " + file + " --fence off --reduced-mode on --json limits");
  ASSERT_EQ(json_shown.status, 0) << json_shown.out;
  const auto limits = nlohmann::json::parse(json_shown.out).at("limits");
  EXPECT_EQ(limits.at("fence").at("on"), false);
  EXPECT_EQ(limits.at("reduced").at("on"), true);
  auto none = run_armctl("arm --arm xarm --fence on limits");
  EXPECT_EQ(none.status, 1) << none.out;
  EXPECT_TRUE(contains(none.out, "the scene sets no fence, nor does the arm file")) << none.out;
}

// The arm file may carry the fence and reduced mode too (where the arm stands for good): in
// force with no scene, switched like a scene's, replaced by a scene's own.
TEST(SceneCli, TheArmFilesFenceHoldsWithoutASceneAndAScenesOwnReplacesIt) {
  const auto dir = temp_dir() / "fenced-arm";
  std::filesystem::create_directories(dir);
  const std::filesystem::path config = std::filesystem::path(ARMCTL_SOURCE_DIR) / "config";
  std::filesystem::copy_file(config / "xarm.urdf", dir / "xarm.urdf", std::filesystem::copy_options::overwrite_existing);
  nlohmann::json arm = nlohmann::json::parse(std::ifstream(config / "xarm.arm.json"));
  arm["fence"] = nlohmann::json::parse(R"({"min": [-300, -300, 0], "max": [150, 300, 450]})");
  arm["reduced"] = nlohmann::json::parse(R"({"joints": {"servo1": [-90, 90]}, "on": false})");
  const std::string arm_file = (dir / "xarm.arm.json").string();
  write(arm_file, arm.dump(2));

  expect_the_fence_and_reduced_mode_hold("--arm " + arm_file);
  // A scene's own fence replaces the arm file's; a scene that sets none keeps it.
  const std::string wider = (dir / "wider.json").string();
  write(wider, R"({"fence": {"min": [-300, -300, 0], "max": [250, 300, 450]}})");
  EXPECT_EQ(run_armctl("arm --arm " + arm_file + " --scene " + wider + " move-to x=200 y=0 z=150").status, 0);
  auto desk = run_armctl("arm --arm " + arm_file + " --scene " + kScene + " move-to x=200 y=0 z=150");
  EXPECT_EQ(desk.status, 1) << desk.out;
  EXPECT_TRUE(contains(desk.out, "would leave the fence")) << desk.out;

  // Checked when the arm file is read, naming the file and the key.
  arm["fence"]["max"][2] = -10;
  write(arm_file, arm.dump(2));
  auto bad = run_armctl("arm --arm " + arm_file + " limits");
  EXPECT_EQ(bad.status, 1) << bad.out;
  EXPECT_TRUE(contains(bad.out, "xarm.arm.json: fence.max: z -10 mm is not above min's 0 mm")) << bad.out;
  arm["fence"]["max"][2] = 450;
  arm["reduced"]["joints"]["servo1"] = nlohmann::json::array({-200, 90});
  write(arm_file, arm.dump(2));
  bad = run_armctl("arm --arm " + arm_file + " limits");
  EXPECT_EQ(bad.status, 1) << bad.out;
  EXPECT_TRUE(contains(bad.out, "xarm.arm.json: reduced.joints.servo1: [-200, 90] deg is not inside joint servo1's own"))
      << bad.out;
}

TEST(SceneCli, AProgramLineThroughTheTableIsRefusedWithItsLine) {
  const auto dir = temp_dir();
  write(dir / "down.prog", "# into the desk\nptp p1\nlin p1 + base(z=-80mm) speed=50mm/s\n");
  write(dir / "down.points", "p1 x=120mm y=120mm z=60mm\n");
  const std::string prog = (dir / "down.prog").string();
  auto check = run_armctl("program check " + prog + " --arm xarm --scene " + kScene);
  EXPECT_EQ(check.status, 1) << check.out;
  EXPECT_TRUE(contains(check.out, "down.prog:3")) << check.out;
  EXPECT_TRUE(contains(check.out, "the table 'desk'")) << check.out;
  // Without the scene the same program checks: only the table refuses it.
  auto bare = run_armctl("program check " + prog + " --arm xarm");
  EXPECT_EQ(bare.status, 0) << bare.out;
  auto run = run_armctl("program run " + prog + " --arm xarm --scene " + kScene + " --json", "2>&1");
  EXPECT_EQ(run.status, 1) << run.out;
  EXPECT_FALSE(contains(run.out, "\"planned\"")) << run.out;  // refused before anything moved
  std::filesystem::remove_all(dir);
}

TEST(SceneCli, AProgramGoesAroundTheBoxWithAvoid) {
  const auto dir = temp_dir();
  write(dir / "behind.prog", "# behind the box\nptp p1\nptp p2\n");
  write(dir / "behind.points", "p1 x=120mm y=120mm z=60mm\np2 x=150mm y=-190mm z=40mm\n");
  const std::string prog = (dir / "behind.prog").string();
  auto direct = run_armctl("program check " + prog + " --arm xarm --scene " + kScene);
  EXPECT_EQ(direct.status, 1) << direct.out;
  EXPECT_TRUE(contains(direct.out, "behind.prog:3")) << direct.out;
  EXPECT_TRUE(contains(direct.out, "with box 'box'")) << direct.out;
  auto around = run_armctl("program check " + prog + " --arm xarm --scene " + kScene + " --avoid --avoid-time 5s");
  EXPECT_EQ(around.status, 0) << around.out;
  EXPECT_TRUE(contains(around.out, "OK on arm 'xarm'")) << around.out;
  auto run = run_armctl("program run " + prog + " --arm xarm --scene " + kScene + " --avoid --avoid-time 5s");
  EXPECT_EQ(run.status, 0) << run.out;
  std::filesystem::remove_all(dir);
}

TEST(SceneCli, ABadSceneFileNamesTheKeyAndOpensNothing) {
  const auto dir = temp_dir();
  write(dir / "bad.json", R"({"objects": [{"name": "box", "box": [60, 0, 100], "at": [170, 0, 50]}]})");
  auto r = run_armctl("arm --arm xarm --scene " + (dir / "bad.json").string() + " move-to x=120 y=120 z=60");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_TRUE(contains(r.out, "bad.json: objects[0].box[1]: 0 is outside the allowed range 0.1..10000")) << r.out;
  auto missing = run_armctl("arm --arm xarm --scene " + (dir / "none.json").string() + " joints");
  EXPECT_EQ(missing.status, 1) << missing.out;
  EXPECT_TRUE(contains(missing.out, "scene file")) << missing.out;
  std::filesystem::remove_all(dir);
}

// The simulators read the scene as the planner does: a bad file is refused with its key before
// anything starts (no pty, no socket).
TEST(SceneCli, TheSimulatorsRefuseABadSceneFileWithItsKey) {
  const auto dir = temp_dir();
  write(dir / "bad.json", R"({"objects": [{"name": "box", "box": [60, 0, 100], "at": [170, 0, 50]}]})");
  for (const std::string& sim : {std::string("sim xarm"), "sim scara --listen " + (dir / "never.sock").string()}) {
    auto r = run_armctl(sim + " --scene " + (dir / "bad.json").string());
    EXPECT_NE(r.status, 0) << sim << ": " << r.out;
    EXPECT_TRUE(contains(r.out, "bad.json: objects[0].box[1]: 0 is outside the allowed range 0.1..10000")) << r.out;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "never.sock"));
  std::filesystem::remove_all(dir);
}

// End to end across processes, in real time: `armctl sim xarm --scene` knows the desk's box;
// the host (`armctl arm` without --scene) sends the arm into it. The servos stall at the box,
// and the host's stall protection stops the arm and names the joint (exit status: a device
// error).
TEST(SceneCli, ARawMoveIntoABoxOnlyTheSimulatorKnowsStallsAndIsNamed) {
  const auto dir = temp_dir();
  const std::string link = (dir / "xarm").string();
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string bin = std::string(ARMCTL_BINARY_DIR) + "/armctl";
    ::freopen("/dev/null", "w", stdout);
    ::execl(bin.c_str(), bin.c_str(), "sim", "xarm", "--scene", kScene.c_str(), "--link", link.c_str(),
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Wait for the link to appear (bounded; the process needs a moment to start).
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!std::filesystem::exists(link) && std::chrono::steady_clock::now() < until) std::this_thread::yield();
  ASSERT_TRUE(std::filesystem::exists(link)) << "armctl sim xarm did not start";
  auto r = run_armctl("arm --arm xarm --device " + link + " move-to x=150 y=-100 z=60 --wait");
  EXPECT_NE(r.status, 0) << r.out;
  EXPECT_TRUE(contains(r.out, "stalled: it stood at")) << r.out;
  EXPECT_TRUE(contains(r.out, "torque released")) << r.out;
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  int st = 0;
  ASSERT_EQ(::waitpid(pid, &st, 0), pid);
  std::filesystem::remove_all(dir);
}

}  // namespace
