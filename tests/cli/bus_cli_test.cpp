// `armctl bus` and `armctl sim scara` end to end: the real binary (ARMCTL_BINARY_DIR/armctl),
// its output, its exit status, and its error messages for bad arguments.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "run_armctl.hpp"

namespace {

using armctl::cli_test::CliRun;

CliRun armctl(const std::string& args) { return armctl::cli_test::run_armctl(args); }
std::string stdout_only(const std::string& args) { return armctl::cli_test::run_armctl(args, "2>/dev/null").out; }

TEST(Cli, VersionIsTheProjects) {
  const CliRun r = armctl("--version");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out, std::string("armctl ") + ARMCTL_VERSION + "\n");
}

// Exit statuses (README "Exit status"): 2 for every usage error (CLI11 had 105, 106, 109).
TEST(Cli, UsageErrorsExitTwo) {
  for (const char* args : {"bus --retries 99 ping", "bus", "frobnicate", "bus ping 1 --nope", "arm move-joints"}) {
    const CliRun r = armctl(args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
  }
  EXPECT_EQ(armctl("--help").status, 0);
}

// A move stopped by Ctrl-C exits 130 (128 + SIGINT), as a shell reports an interrupted
// command; it exited 1, like any failure.
TEST(Cli, AMoveStoppedByCtrlCExits130) {
  int out[2];
  ASSERT_EQ(::pipe(out), 0);
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::dup2(out[1], STDOUT_FILENO);
    ::dup2(out[1], STDERR_FILENO);
    const std::string bin = std::string(ARMCTL_BINARY_DIR) + "/armctl";
    // The emulated xArm runs in real time: the square's 8 s of lines are under way when
    // SIGINT comes.
    const std::string square = std::string(ARMCTL_SOURCE_DIR) + "/examples/paths/xarm-square.path";
    ::execl(bin.c_str(), bin.c_str(), "arm", "path", square.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::close(out[1]);
  // The first move's report says the lines run now (no fixed sleep).
  char buffer[256];
  std::string rest;
  while (rest.find("done in") == std::string::npos) {
    const ssize_t n = ::read(out[0], buffer, sizeof buffer);
    ASSERT_GT(n, 0) << "the path ended early: " << rest;
    rest.append(buffer, std::size_t(n));
  }
  ASSERT_EQ(::kill(pid, SIGINT), 0);
  for (ssize_t n; (n = ::read(out[0], buffer, sizeof buffer)) > 0;) rest.append(buffer, std::size_t(n));
  ::close(out[0]);
  int st = 0;
  ASSERT_EQ(::waitpid(pid, &st, 0), pid);
  ASSERT_TRUE(WIFEXITED(st)) << rest;
  EXPECT_EQ(WEXITSTATUS(st), 130) << rest;
}

TEST(BusCli, ReadsEveryJointOfTheEmbeddedSim) {
  const CliRun r = armctl("bus position all");
  EXPECT_EQ(r.status, 0) << r.out;
  for (int j = 1; j <= 7; ++j) EXPECT_NE(r.out.find("joint " + std::to_string(j) + ": position 0"), std::string::npos) << r.out;
}

TEST(BusCli, JsonOutputIsOneDocument) {
  // On one line, as every other --json output (it was 42 lines for `position all`).
  const std::string all = stdout_only("bus --json position all");
  EXPECT_EQ(std::count(all.begin(), all.end(), '\n'), 1) << all;
  const auto doc = nlohmann::json::parse(stdout_only("bus --json ping 3 -77"));
  EXPECT_EQ(doc["command"], "ping");
  EXPECT_TRUE(doc["ok"].get<bool>());
  ASSERT_EQ(doc["joints"].size(), 1u);
  EXPECT_EQ(doc["joints"][0]["joint"], 3);
  EXPECT_EQ(doc["joints"][0]["value"], -77);
}

TEST(BusCli, ADeadJointIsShownPerJointAndFailsTheCommand) {
  const CliRun r = armctl("bus --device 'sim?dead=6' position all");
  EXPECT_NE(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("joint 6: FAILED no answer (990)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1 of 7 joints failed"), std::string::npos) << r.out;
  for (int j : {1, 2, 3, 4, 5, 7}) {
    EXPECT_NE(r.out.find("joint " + std::to_string(j) + ": position 0"), std::string::npos) << r.out;
  }
  // One line of results, then (the command failed) the error line every --json command ends with.
  const std::string out = stdout_only("bus --device 'sim?dead=2,6' --json position all");
  ASSERT_EQ(std::count(out.begin(), out.end(), '\n'), 2) << out;
  const auto doc = nlohmann::json::parse(out.substr(0, out.find('\n')));
  const auto error = nlohmann::json::parse(out.substr(out.find('\n') + 1));
  EXPECT_EQ(error["event"], "error") << out;
  EXPECT_EQ(error["exit_status"], 1) << out;
  EXPECT_FALSE(doc["ok"].get<bool>());
  ASSERT_EQ(doc["joints"].size(), 7u);
  for (const auto& row : doc["joints"]) {
    const int j = row["joint"].get<int>();
    EXPECT_EQ(row["ok"].get<bool>(), j != 2 && j != 6) << row;
    if (j == 2 || j == 6) {
      EXPECT_EQ(row["error"]["code"], 990) << row;
    }
  }
}

TEST(BusCli, EveryCommandRunsOnTheEmbeddedSim) {
  for (const char* args : {"ping all", "home 1", "pid all on", "pid 2 off", "target all", "number 7", "drive-dist 1 10",
                           "drive-dist-max all -5", "drive-to all 100", "speed all 50", "zone 3 4", "reached all",
                           "wait all --timeout 5", "--verify --retries 2 drive-to 2 300"}) {
    const CliRun r = armctl(std::string("bus ") + args);
    EXPECT_EQ(r.status, 0) << args << "\n" << r.out;
  }
}

TEST(BusCli, BadArgumentsGetAClearMessageAndNonZeroStatus) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"bus drive-to 3 abc", "VALUE 'abc'"},
      {"bus drive-to 3 40000", "-32768..32767"},
      {"bus speed 1 150", "0..100"},
      {"bus zone 1 -1", "0..32767"},
      {"bus position 9", "JOINT"},
      {"bus position 0", "JOINT"},
      {"bus pid 1 maybe", "on or off"},
      {"bus --device tcp:1.2.3.4 position", "unknown kind of device"},
      {"bus --device serial:/dev/ttyAMA0 position", "needs select="},
      {"bus --device unix:/tmp/armctl-no-such.sock position", "armctl sim scara"},
      {"bus frobnicate", "unknown command 'frobnicate'; allowed: ping"},
      {"bus drive-to 3", "value"},
      {"bus", "a command is required; allowed: ping"},
      {"bus ping 1 ''", "VALUE '' is not allowed"},
      {"bus wait --timeout nan", "--timeout: nan is outside 0..3600 s, 0 excluded"},
      {"bus wait --timeout 0", "--timeout: 0 is outside 0..3600 s, 0 excluded"},
      {"bus wait --timeout soon", "--timeout: 'soon' is not a number (allowed 0..3600 s, 0 excluded)"},
      {"sim scara --link /tmp/armctl-x --state-dir /tmp/armctl-y", "belong to --robot-commands"},
      // Numeric options name the option, the value and the range (not "Could not convert").
      {"bus --retries 99 ping", "--retries: 99 is outside 0..10"},
      {"bus --retries -1 ping", "--retries: -1 is outside 0..10"},
      // One message for every wrong --baud, listing the standard rates.
      {"sim scara --baud 99999999999", "--baud: 99999999999 is not a standard rate (allowed: "},
      {"sim scara --baud fast", "--baud: fast is not a standard rate (allowed: "},
      {"sim scara --baud 0", "--baud: 0 is not a standard rate (allowed: "},
      {"sim xarm --baud 99999999999", "--baud: 99999999999 is not a standard rate (allowed: "},
      {"sim xarm --baud 12345", "--baud: 12345 is not a standard rate (allowed: "},
      {"sim xarm --battery -1", "--battery: -1 is outside 4500..12000"},
      {"sim xarm --battery 4294967296", "--battery: 4294967296 is outside 4500..12000"},
      {"bus --device 'sim?baud=99999999999' ping", "baud 99999999999 is outside 1..4000000"},
      // Files the CLI reads: a directory is refused naming the path.
      {"bus --device 'sim?config=/tmp' ping", "simulator config /tmp is not a regular file (a directory)"},
      {"sim scara --config /tmp", "simulator config /tmp is not a regular file (a directory)"},
      {"sim scara --arm /tmp", "simulator config /tmp is not a regular file (a directory)"},
      {"controller --arm /tmp", "arm controller config /tmp is not a regular file (a directory)"},
  };
  for (const auto& [args, want] : cases) {
    const CliRun r = armctl(args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_NE(r.out.find(want), std::string::npos) << args << "\n" << r.out;
  }
}

// A config key holding a terminal escape (JSON "\u001b") reaches stderr escaped.
TEST(BusCli, AConfigKeyWithControlCharactersIsShownEscaped) {
  const std::string path = "/tmp/armctl-escape-key-" + std::to_string(::getpid()) + ".json";
  {
    // The shipped arm file with one unknown key in front of its simulator section: the key is
    // what gets reported.
    std::ifstream in(std::string(ARMCTL_SOURCE_DIR) + "/config/scara.arm.json");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string section = "\"simulator\": {";
    const auto at = text.find(section);
    ASSERT_NE(at, std::string::npos) << "config/scara.arm.json has no simulator section";
    text.insert(at + section.size(), "\"\\u001b]0;owned\\u0007\": 1, ");
    std::ofstream(path) << text;
  }
  const CliRun r = armctl("bus --device 'sim?config=" + path + "' ping");
  std::remove(path.c_str());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("\\x1b]0;owned\\x07"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find('\x1b'), std::string::npos) << r.out;
}

TEST(SimScaraCli, KeepsStateBetweenCommandsAndStopsCleanly) {
  const std::string sock = "/tmp/armctl-cli-test-" + std::to_string(::getpid()) + ".sock";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string bin = std::string(ARMCTL_BINARY_DIR) + "/armctl";
    ::freopen("/dev/null", "w", stdout);
    ::execl(bin.c_str(), bin.c_str(), "sim", "scara", "--listen", sock.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Wait for the socket to appear (bounded; the process needs a moment to start).
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (::access(sock.c_str(), F_OK) != 0 && std::chrono::steady_clock::now() < until) {
    std::this_thread::yield();
  }
  ASSERT_EQ(::access(sock.c_str(), F_OK), 0) << "armctl sim scara did not listen";
  const std::string dev = "bus --device unix:" + sock + " ";
  EXPECT_EQ(armctl(dev + "drive-to 2 600").status, 0);
  const CliRun w = armctl(dev + "wait 2 --timeout 10");
  EXPECT_EQ(w.status, 0) << w.out;
  const CliRun t = armctl(dev + "target 2");
  EXPECT_NE(t.out.find("target 600"), std::string::npos) << t.out;
  const CliRun p = armctl(dev + "--json position 2");
  const auto pos = nlohmann::json::parse(p.out.substr(p.out.find('{')));
  EXPECT_LE(std::abs(pos["joints"][0]["value"].get<int>() - 600), 10) << p.out;

  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  int st = 0;
  ASSERT_EQ(::waitpid(pid, &st, 0), pid);
  EXPECT_TRUE(WIFEXITED(st)) << "killed by a signal instead of exiting";
  EXPECT_EQ(WEXITSTATUS(st), 0);
  EXPECT_NE(::access(sock.c_str(), F_OK), 0) << "socket file left behind";
}

TEST(SimScaraCli, BadBaudIsRefused) {
  const CliRun r = armctl("sim scara --listen /tmp/armctl-never.sock --baud 12345");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("not a standard rate"), std::string::npos) << r.out;
  // The same mistake, the same exit status, whatever the number (was 105 for 0, 1 for 12345).
  EXPECT_EQ(armctl("sim scara --listen /tmp/armctl-never.sock --baud 0").status, r.status);
}

}  // namespace

namespace {

TEST(BusCli, FaultsShowsEveryJointsFaultsCountersAndSettings) {
  const CliRun r = armctl("bus faults all");
  EXPECT_EQ(r.status, 0) << r.out;
  for (int j = 1; j <= 7; ++j) {
    EXPECT_NE(r.out.find("joint " + std::to_string(j) + ": faults: none; lost bus events 0"), std::string::npos) << r.out;
  }
  EXPECT_NE(r.out.find("last reset: power-on; motor polarity original, standard master"), std::string::npos) << r.out;
  const auto doc = nlohmann::json::parse(stdout_only("bus --json faults 3"));
  ASSERT_EQ(doc["joints"].size(), 1u);
  const auto& v = doc["joints"][0]["value"];
  EXPECT_EQ(v["faults"], nlohmann::json::array());
  EXPECT_EQ(v["fault_bits"], 0);
  EXPECT_EQ(v["encoder_edges_lost"], 0);
  EXPECT_EQ(v["motor_polarity"], "original");
  EXPECT_EQ(v["master"], "standard");
  EXPECT_EQ(v["reset_cause"], "power-on");
}

TEST(BusCli, ClearFaultsAnswersPerJoint) {
  const CliRun r = armctl("bus clear-faults all");
  EXPECT_EQ(r.status, 0) << r.out;
  for (int j = 1; j <= 7; ++j) EXPECT_NE(r.out.find("joint " + std::to_string(j) + ": faults cleared"), std::string::npos) << r.out;
  const CliRun dead = armctl("bus --device 'sim?dead=4' clear-faults 4");
  EXPECT_NE(dead.status, 0);
  EXPECT_NE(dead.out.find("joint 4: FAILED no answer (990)"), std::string::npos) << dead.out;
}

TEST(BusCli, TheSimulatedArmOffersLegacyMasterJoints) {
  const CliRun r = armctl("bus --device 'sim?dialect=legacy' faults 2");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("legacy master"), std::string::npos) << r.out;
  EXPECT_EQ(armctl("bus --device 'sim?dialect=legacy' speed 3 200").status, 0);
  EXPECT_NE(armctl("bus --device 'sim?dialect=legacy' speed 3 256").status, 0);
  const CliRun ping = armctl("bus --device 'sim?dialect=legacy' ping 5 42");
  EXPECT_EQ(ping.status, 0) << ping.out;
  EXPECT_NE(ping.out.find("joint 5: answered, echo 42"), std::string::npos) << ping.out;
}

}  // namespace
