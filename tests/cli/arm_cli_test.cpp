// `armctl arm` end to end: the real binary on both embedded simulated arms; output in deg
// and mm, --json documents, exit status, and the messages for bad values (nothing moves).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "run_armctl.hpp"

namespace {

using armctl::cli_test::run_armctl;

class ArmCli : public ::testing::Test {
 protected:
  void SetUp() override {
    state = std::filesystem::temp_directory_path() /
            // One directory per test and process: CTest runs these tests side by side.
            ("armctl-arm-cli-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "-" +
             std::to_string(::getpid()));
    std::filesystem::create_directories(state);
    ::setenv("ARMCTL_STATE_DIR", state.c_str(), 1);
  }
  void TearDown() override { std::filesystem::remove_all(state); }
  std::filesystem::path state;
};

using armctl::cli_test::contains;
using armctl::cli_test::json_lines;

TEST_F(ArmCli, JointsAndPoseOfBothArms) {
  auto x = run_armctl("arm joints");
  EXPECT_EQ(x.status, 0) << x.out;
  EXPECT_TRUE(contains(x.out, "servo6")) << x.out;
  EXPECT_TRUE(contains(x.out, "(device 500)")) << x.out;
  auto s = run_armctl("arm --arm scara joints");
  EXPECT_EQ(s.status, 0) << s.out;
  EXPECT_TRUE(contains(s.out, "Z             150.000 mm")) << s.out;
  auto p = run_armctl("arm --arm scara --json pose", "2>/dev/null");
  ASSERT_EQ(p.status, 0);
  auto doc = nlohmann::json::parse(p.out);
  EXPECT_NEAR(doc["pose"]["x_mm"].get<double>(), 685.0, 1e-6);  // 255 + 255 + 175, stretched out
}

TEST_F(ArmCli, HealthOfBothArmsAsTheDashboardShowsIt) {
  // The emulated xArm: its battery; it ignores JointFaultRead, so no faults and no error.
  auto x = run_armctl("arm --json health", "2>/dev/null");
  ASSERT_EQ(x.status, 0) << x.out;
  const auto xd = nlohmann::json::parse(x.out);
  EXPECT_GT(xd["health"]["battery_volts"].get<double>(), 6.0);
  EXPECT_TRUE(xd["health"]["faults"].empty());
  // The SCARA on the embedded joint bus: no supply reading, every joint's fault words clear.
  auto s = run_armctl("arm --arm scara health");
  EXPECT_EQ(s.status, 0) << s.out;
  EXPECT_TRUE(contains(s.out, "battery  n/a")) << s.out;
  EXPECT_TRUE(contains(s.out, "faults   none")) << s.out;
}

TEST_F(ArmCli, ClearFaultsOnBothArms) {
  // The emulated xArm holds no joint faults (it ignores armctl's extension): nothing to clear.
  auto x = run_armctl("arm --json clear-faults", "2>/dev/null");
  ASSERT_EQ(x.status, 0) << x.out;
  EXPECT_EQ(nlohmann::json::parse(x.out)["faults_cleared"], true);
  // The SCARA's joints each get clear_faults on the bus and answer it.
  auto s = run_armctl("arm --arm scara clear-faults");
  EXPECT_EQ(s.status, 0) << s.out;
  EXPECT_TRUE(contains(s.out, "faults cleared")) << s.out;
}

TEST_F(ArmCli, MoveToAPointInMillimetresOnBothArms) {
  for (const char* cmd : {"arm --json move-to x=150 y=50 z=150 --wait",
                          "arm --arm scara --json move-to x=400 y=100 z=300 --wait --time 2s"}) {
    auto r = run_armctl(cmd, "2>/dev/null");
    ASSERT_EQ(r.status, 0) << cmd;
    const auto docs = json_lines(r.out);
    ASSERT_EQ(docs.size(), 2u) << r.out;
    // First the plan (as every app answers a move), then the pose read back.
    EXPECT_EQ(docs[0]["event"], "planned") << r.out;
    EXPECT_GT(docs[0]["duration_s"].get<double>(), 0.1) << r.out;
    EXPECT_FALSE(docs[0]["targets"].empty()) << r.out;
    EXPECT_LT(docs[1]["position_error_mm"].get<double>(), 2.0) << cmd << ": " << r.out;
  }
}

// `arm path` on the embedded xArm: the example square as --json events (planned, progress,
// one done per piece with its errors), then bad files refused before anything moves.
TEST_F(ArmCli, PathFilesRunAsJsonEventsAndBadOnesMoveNothing) {
  const std::string square = std::string(ARMCTL_SOURCE_DIR) + "/examples/paths/xarm-square.path";
  auto r = run_armctl("arm --json path " + square, "2>&1");
  ASSERT_EQ(r.status, 0) << r.out;
  std::vector<nlohmann::json> done;
  nlohmann::json planned;
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);) {
    const auto e = nlohmann::json::parse(line);
    if (!e.contains("event")) continue;  // the final joints document
    if (e["event"] == "planned") planned = e;
    if (e["event"] == "done") done.push_back(e);
  }
  EXPECT_EQ(planned["moves"], 5) << r.out;
  EXPECT_EQ(planned["pieces"], 2) << r.out;  // the PTP, then the four blended LINs
  ASSERT_EQ(done.size(), 2u) << r.out;
  for (const auto& e : done) {
    EXPECT_GE(e["held_s"].get<double>(), 0.0);
    EXPECT_GT(e["points"].get<int>(), 10);
  }
  // The square's path error: the demo shows 0.8 mm; the target is twice a LIN's quantization
  // limit on the xArm, 3.27 mm (docs/benchmarks.md, Motion).
  EXPECT_LT(done[1]["path_error_mm"].get<double>(), 3.27) << done[1].dump();

  const auto bad = state / "bad.path";
  for (const auto& [text, says] : std::vector<std::pair<std::string, std::string>>{
           {"ptp x=180mm y=-40mm z=100mm pitch=50deg\nlin x=180mm y=40mm z=100mm speed=-4mm/s\n",
            "bad.path:2:34: found '-4mm/s', expected a speed within 0.1..500 mm/s"},
           {"ptp x=180mm y=-40mm z=100mm pitch=50deg\nlin x=1e308mm y=40mm z=100mm speed=40mm/s\n",
            "lines 2..2: segment 1 (LIN): target: x 1e+308 mm is beyond reach: arm 'xarm' reaches at most"},
           {"ptp x=180mm y=-40mm z=100mm pitch=50deg\nlin x=340mm y=40mm z=100mm speed=40mm/s\n",
            "segment 1 (LIN): at "}}) {
    {
      std::ofstream out(bad);
      out << text;
    }
    auto refused = run_armctl("arm --json path " + bad.string(), "2>&1");
    EXPECT_NE(refused.status, 0) << text;
    EXPECT_TRUE(contains(refused.out, says)) << refused.out;
    // Nothing planned, nothing moved: the one event is the error.
    EXPECT_FALSE(contains(refused.out, "\"event\":\"planned\"")) << refused.out;
    EXPECT_FALSE(contains(refused.out, "\"event\":\"progress\"")) << refused.out;
    EXPECT_TRUE(contains(refused.out, "{\"event\":\"error\",\"exit_status\":1,")) << refused.out;
  }
  auto stop = run_armctl("arm stop");
  EXPECT_EQ(stop.status, 0) << stop.out;
  EXPECT_TRUE(contains(stop.out, "stopped")) << stop.out;
}

TEST_F(ArmCli, MoveJointsByNameOrNumberWithUnits) {
  auto r = run_armctl("arm --arm scara move-joints SHOULDER=30deg 3=-0.2rad Z=100mm --wait");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(contains(r.out, "SHOULDER       30.0")) << r.out;
  EXPECT_TRUE(contains(r.out, "Z             100.0")) << r.out;
}

TEST_F(ArmCli, IkPrintsEverySolutionAndMovesNothing) {
  auto r = run_armctl("arm --arm scara --json ik x=300 y=200 z=250 roll=180 pitch=0 yaw=30", "2>/dev/null");
  ASSERT_EQ(r.status, 0) << r.out;
  auto doc = nlohmann::json::parse(r.out);
  EXPECT_GE(doc["solutions"].size(), 2u) << r.out;  // elbow left and right at least
}

TEST_F(ArmCli, CalibrateZeroRewritesACopyOfTheArmFile) {
  namespace fs = std::filesystem;
  for (const char* f : {"scara.arm.json", "scara.urdf"})
    fs::copy_file(fs::path(ARMCTL_SOURCE_DIR) / "config" / f, state / f);
  const std::string arm = (state / "scara.arm.json").string();
  // The embedded simulated arm starts with every joint at clicks 0: SHOULDER reads 0 deg
  // already, Z reads 150 mm. Zeroing Z makes "here" 0 mm.
  auto r = run_armctl("arm --arm " + arm + " calibrate zero Z");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(contains(r.out, "Z: zero moved by 150.000 mm")) << r.out;
  auto j = run_armctl("arm --arm " + arm + " joints");
  EXPECT_TRUE(contains(j.out, "Z               0.000 mm")) << j.out;
  // Coupled wrist joints only together; nothing written when refused.
  auto one = run_armctl("arm --arm " + arm + " calibrate zero SKE");
  EXPECT_NE(one.status, 0);
  EXPECT_TRUE(contains(one.out, "coupled")) << one.out;
}

// --time 0 (or 1e-300, 0.1) moved servo6 at twice the 180 deg/s its arm file allows: the
// move is stretched to the limits and says so.
TEST_F(ArmCli, ATimeShorterThanTheLimitsAllowIsStretchedAndSaysSo) {
  for (const char* time : {"0", "1e-300", "0.1s"}) {
    auto r = run_armctl(std::string("arm move-joints servo6=1.7rad --time ") + time + " --wait", "2>&1");
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_TRUE(contains(r.out, std::string("note: --time ") + time +
                                    " is too short for joint servo6 to move 97.403 deg within its limits (180.000 "
                                    "deg/s): the move takes "))
        << r.out;
  }
  auto fine = run_armctl("arm move-joints servo6=10deg --time 2s --wait", "2>&1");
  EXPECT_EQ(fine.status, 0) << fine.out;
  EXPECT_FALSE(contains(fine.out, "note:")) << fine.out;
}

TEST_F(ArmCli, BadValuesAreRefusedClearly) {
  struct Case {
    const char* args;
    const char* says;
  };
  const Case cases[] = {
      {"arm move-joints servo6=200deg", "outside its limits"},
      {"arm move-joints servo6=30mm", "is a length, but this is an angle"},
      {"arm move-joints servo6=nan", "not a finite number"},
      {"arm move-joints servo6=30", "has no unit"},
      {"arm move-joints wrist=3deg", "has no joint 'wrist'"},
      {"arm move-joints servo6=3deg servo6=4deg", "given twice"},
      {"arm move-to x=2000 y=0 z=0", "reach"},
      {"arm move-to x=100 y=0", "z is missing"},
      {"arm move-to x=100 y=0 z=100 w=3", "not a pose key"},
      {"arm move-to x=100 y=0 z=100 --elbow sideways", "--elbow 'sideways'"},
      {"arm move-joints servo6=3deg --speed 0%", "--speed (of the joints' velocity limits): '0%' is too small; allowed 0.1..100 %"},
      {"arm move-joints servo6=3deg --speed 1e-300%", "'1e-300%' is too small; allowed 0.1..100 %"},
      {"arm move-joints servo6=3deg --speed 50", "'50' has no unit; write a percentage like 50%"},
      // Refused before planning (a heap-buffer-overflow in the path check once), with the reach.
      {"arm move-to x=1e200 y=0 z=100 --linear", "segment 1 (LIN): target: x 1e+200 mm is beyond reach: arm 'xarm' reaches at most"},
      {"arm move-to x=1e200 y=0 z=100", "the tool target: x 1e+200 mm is beyond reach"},
      {"arm move-to x=200 y=0 z=100 --linear --speed 1e-300mm/s", "--speed: '1e-300mm/s' is too slow; allowed 0.1..500 mm/s"},
      {"arm move-to x=200 y=0 z=100 --linear --override 50",
       "--override (of the programmed speeds): '50' has no unit; write a percentage like 50%, within 0.1..100 %"},
      {"arm move-to x=200 y=0 z=100 --linear --override 1e-300%", "'1e-300%' is too small; allowed 0.1..100 %"},
      {"arm move-joints servo6=3deg --time -1s", "--time '-1s'"},
      {"arm move-joints servo6=3deg --time 1s --speed 10%", "cannot be used together"},
      {"arm gripper half", "open, close"},
      {"arm torque maybe", "on or off"},
      {"arm --arm /nonexistent.json joints", "no such file"},
      {"arm --arm scara --device sim?baud=7 joints", "baud"},
  };
  for (const auto& c : cases) {
    auto r = run_armctl(c.args);
    EXPECT_NE(r.status, 0) << c.args;
    EXPECT_TRUE(contains(r.out, c.says)) << c.args << ": " << r.out;
  }
}

// --json output: one line per document, numbers as people read them (the SCARA's tool roll is
// 180 deg, once printed as 179.99999999999997), and under --json a failure is a JSON line on
// stdout too, with its kind and exit status (the message stays on stderr).
TEST_F(ArmCli, JsonOutputIsTidyAndFailuresAreJsonToo) {
  auto pose = run_armctl("arm --arm scara --json pose", "2>/dev/null");
  ASSERT_EQ(pose.status, 0) << pose.out;
  EXPECT_TRUE(contains(pose.out, "\"roll_deg\":180.0,")) << pose.out;
  EXPECT_EQ(std::count(pose.out.begin(), pose.out.end(), '\n'), 1) << pose.out;

  auto stop = run_armctl("stop --json", "2>/dev/null");
  ASSERT_EQ(stop.status, 0) << stop.out;
  EXPECT_EQ(nlohmann::json::parse(stop.out)["event"], "stopped") << stop.out;

  auto refused = run_armctl("arm --json move-joints servo6=200deg", "2>/dev/null");
  EXPECT_EQ(refused.status, 1);
  const auto error = nlohmann::json::parse(refused.out);
  EXPECT_EQ(error["event"], "error");
  EXPECT_EQ(error["kind"], "invalid argument");  // as `bus --json` names kinds
  EXPECT_EQ(error["exit_status"], 1);
  EXPECT_TRUE(contains(error["message"].get<std::string>(), "outside its limits")) << refused.out;
  auto on_stderr = run_armctl("arm --json move-joints servo6=200deg", "2>&1 >/dev/null");
  EXPECT_TRUE(contains(on_stderr.out, "outside its limits")) << on_stderr.out;

  auto usage = run_armctl("arm --json frobnicate", "2>/dev/null");
  EXPECT_EQ(usage.status, 2);
  EXPECT_EQ(nlohmann::json::parse(usage.out)["kind"], "usage") << usage.out;
  // Without --json, nothing on stdout.
  EXPECT_EQ(run_armctl("arm move-joints servo6=200deg", "2>/dev/null").out, "");
}

}  // namespace

namespace {

// Any command: a failed write of the output is an error, a closed or full stderr never
// turns exit status 1 into an abort, and a file that is not a tty is named as such.
TEST(CliOutput, FailedWritesAndNonTtyDevicesAreErrors) {
  auto full = run_armctl("arm joints", "2>&1 >/dev/full");  // stderr to the pipe, stdout full
  EXPECT_EQ(full.status, 1) << full.out;
  EXPECT_TRUE(contains(full.out, "could not write the output")) << full.out;
  EXPECT_EQ(run_armctl("arm move-joints servo6=300deg", "2>&-").status, 1);
  EXPECT_EQ(run_armctl("arm move-joints servo6=300deg", "2>/dev/full").status, 1);
  auto not_tty = run_armctl("xarm --device serial:/etc/passwd battery");
  EXPECT_EQ(not_tty.status, 1) << not_tty.out;
  EXPECT_TRUE(contains(not_tty.out, "/etc/passwd is not a serial port or pty")) << not_tty.out;
}

}  // namespace
