// `armctl xarm --device hid ...` end to end on a fake xArm board: armctl_fake_hid is the
// armctl CLI with hidapi's functions replaced by the fake (fake_hidapi.cpp), so the real
// node lock, HidDevice, HidLink, session and `watch` run. The fake keeps real time (it is a
// device in another process); the delays are the board's, nothing here waits for a state.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "../cli/run_armctl.hpp"

namespace {

namespace fs = std::filesystem;

struct Outcome {
  int status = -1;
  std::string out;
  std::string err;
  long long elapsed_ms = 0;
};

using armctl::cli_test::read_some;

// Runs armctl_fake_hid with `args` and `env` added to the environment, to the end.
Outcome run(const std::vector<std::string>& args, const std::map<std::string, std::string>& env) {
  const auto start = std::chrono::steady_clock::now();
  int out[2], err[2];
  if (::pipe2(out, O_CLOEXEC) != 0 || ::pipe2(err, O_CLOEXEC) != 0) std::abort();
  const pid_t pid = ::fork();
  if (pid < 0) std::abort();
  if (pid == 0) {
    ::dup2(out[1], 1);
    ::dup2(err[1], 2);
    for (const auto& [k, v] : env) ::setenv(k.c_str(), v.c_str(), 1);
    std::vector<char*> argv{const_cast<char*>(ARMCTL_FAKE_HID_BINARY)};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(ARMCTL_FAKE_HID_BINARY, argv.data());
    ::_exit(127);
  }
  ::close(out[1]);
  ::close(err[1]);
  Outcome o;
  pollfd fds[2] = {{out[0], POLLIN, 0}, {err[0], POLLIN, 0}};
  bool open[2] = {true, true};
  while (open[0] || open[1]) {
    for (int i = 0; i < 2; ++i) fds[i].fd = open[i] ? (i == 0 ? out[0] : err[0]) : -1;
    if (::poll(fds, 2, -1) < 0 && errno != EINTR) break;
    if (open[0] && (fds[0].revents & (POLLIN | POLLHUP))) open[0] = read_some(out[0], o.out);
    if (open[1] && (fds[1].revents & (POLLIN | POLLHUP))) open[1] = read_some(err[0], o.err);
  }
  int st = 0;
  ::waitpid(pid, &st, 0);
  ::close(out[0]);
  ::close(err[0]);
  o.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  o.elapsed_ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                     std::chrono::steady_clock::now() - start)
                     .count();
  return o;
}

using armctl::cli_test::contains;
using armctl::cli_test::json_lines;
std::vector<std::string> split(const std::string& text) { return armctl::cli_test::split_args(text); }

class HidCli : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "armctl-hid-cli-XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
    node_ = (dir_ / "hidraw0").string();
    std::ofstream(node_).put('\0');
    log_ = (dir_ / "board.log").string();
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  // `armctl xarm ARGS` with the fake board behaving as `behaviour` says.
  Outcome xarm(const std::string& args, const std::string& behaviour = "",
               const std::string& product = "LOBOT") {
    auto argv = split(args);
    argv.insert(argv.begin(), "xarm");
    return run(argv, {{"ARMCTL_FAKE_HID_NODE", node_},
                      {"ARMCTL_FAKE_HID_BEHAVIOUR", behaviour},
                      {"ARMCTL_FAKE_HID_PRODUCT", product},
                      {"ARMCTL_FAKE_HID_LOG", log_},
                      {"ARMCTL_STATE_DIR", (dir_ / "state").string()}});
  }
  std::vector<std::string> log_lines() const {
    std::ifstream in(log_);
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
  }

  fs::path dir_;
  std::string node_;
  std::string log_;
};

TEST_F(HidCli, PositionsOnABoardThatIsSlowAfterOpeningAndSlowToAnswer) {
  // First answer only 1.2 s after opening, then 450 ms per reply.
  const Outcome r = xarm("--device hid --json positions", "reply_delay_ms=450,hold_ms=1200");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  const auto docs = json_lines(r.out);
  ASSERT_EQ(docs.size(), 1u) << r.out;
  EXPECT_EQ(docs[0]["positions"].size(), 6u);
  EXPECT_GE(r.elapsed_ms, 1200 + 450);  // first contact held, then a 450 ms position read
  std::printf("measured: positions on a board answering 1.2 s after open + 450 ms: %lld ms\n",
              r.elapsed_ms);
}

TEST_F(HidCli, DeafBoardAfterOpenIsAskedAgain) {
  const Outcome ok = xarm("--device hid battery", "deaf_ms=1200,reply_delay_ms=50");
  ASSERT_EQ(ok.status, 0) << ok.out << ok.err;
  EXPECT_TRUE(contains(ok.out, "battery: 7500 mV")) << ok.out;
  std::printf("measured: battery on a board deaf for 1.2 s after open: %lld ms\n", ok.elapsed_ms);
  // With the old single short wait (every attempt inside the deaf spell) it cannot work,
  // and the error says what to check.
  const Outcome bad = xarm("--device hid --timeout 300 battery", "deaf_ms=1200,reply_delay_ms=50");
  EXPECT_EQ(bad.status, 1) << bad.out;
  EXPECT_TRUE(contains(bad.err, "did not answer its first request")) << bad.err;
  EXPECT_TRUE(contains(bad.err, "sent 3 times")) << bad.err;
  EXPECT_TRUE(contains(bad.err, "fwupd")) << bad.err;
}

TEST_F(HidCli, WatchRidesOutMissedRepliesAndStopsAfterSeveralInARow) {
  // Reply 1 answers first contact, 2 the first poll; 3 is lost (resent, 4 answers); 5..10
  // are lost: two polls in a row fail and watch stops (--max-missed 2).
  const Outcome r = xarm("--device hid --timeout 100 --json watch --interval 20 --max-missed 2",
                         "drop=3+5+6+7+8+9+10");
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  const auto docs = json_lines(r.out);
  ASSERT_EQ(docs.size(), 6u) << r.out;  // the last: the error line of a failed --json command
  EXPECT_EQ(docs[5]["event"], "error");
  EXPECT_EQ(docs[5]["exit_status"], 1);
  EXPECT_TRUE(docs[0].contains("positions"));
  EXPECT_EQ(docs[1]["resent"], 1);
  EXPECT_EQ(docs[1]["missed_total"], 1);
  EXPECT_TRUE(docs[2].contains("positions"));
  EXPECT_EQ(docs[3]["missed_in_row"], 1);
  EXPECT_EQ(docs[4]["missed_in_row"], 2);
  EXPECT_EQ(docs[4]["missed_total"], 1 + 3 + 3);
  EXPECT_TRUE(contains(r.err, "2 polls in a row got no usable reply")) << r.err;
}

TEST_F(HidCli, WatchTextShowsMissedReplies) {
  const Outcome r = xarm("--device hid --timeout 100 watch --interval 20 --max-missed 1",
                         "drop=3+4+5");
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_TRUE(contains(r.out, "1=500")) << r.out;
  EXPECT_TRUE(contains(r.out, "missed (1 in a row, 3 in all)")) << r.out;
}

TEST_F(HidCli, ServoOffGoesOneFramePerServoAndEveryServoGoesLimp) {
  const Outcome r = xarm("--device hid off", "ignore_combined_off=1");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  int single = 0;
  std::string last_torque;
  for (const auto& l : log_lines()) {
    if (contains(l, "cmd=20 count=1 ")) ++single;
    EXPECT_FALSE(contains(l, "cmd=20 count=6")) << l;
    last_torque = l.substr(l.find("torque=") + 7, 6);
  }
  EXPECT_EQ(single, 6);
  EXPECT_EQ(last_torque, "000000");
  EXPECT_TRUE(contains(log_lines().back(), "cmd=21")) << "read back after the off frames";
}

TEST_F(HidCli, SecondArmctlIsRefusedNamingTheHolder) {
  const int fd = ::open(node_.c_str(), O_RDONLY);
  ASSERT_EQ(::flock(fd, LOCK_EX), 0);
  const Outcome r = xarm("--device hid battery");
  ::close(fd);
  EXPECT_EQ(r.status, 1);
  EXPECT_TRUE(contains(r.err, "another program is using the board")) << r.err;
  EXPECT_TRUE(contains(r.err, "(pid " + std::to_string(::getpid()) + ")")) << r.err;
  EXPECT_TRUE(log_lines().empty()) << "nothing was sent";
}

TEST_F(HidCli, ProgramThatHasTheNodeOpenIsNamedInAWarning) {
  const int fd = ::open(node_.c_str(), O_RDONLY);  // open, no lock: like a Python script
  const Outcome r = xarm("--device hid battery");
  ::close(fd);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(contains(r.err, "warning: " + node_ + " is also open in")) << r.err;
  EXPECT_TRUE(contains(r.err, "(pid " + std::to_string(::getpid()) + ")")) << r.err;
}

TEST_F(HidCli, ExplicitPathOpensACloneWithAWarning) {
  const Outcome none = xarm("--device hid battery", "", "CLONE");
  EXPECT_EQ(none.status, 1);
  EXPECT_TRUE(contains(none.err, "no xArm board found")) << none.err;
  const Outcome r = xarm("--device hid:" + node_ + " battery", "", "CLONE");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "battery: 7500 mV")) << r.out;
  EXPECT_TRUE(contains(r.err, "warning: " + node_ + " is 0483:5750 \"CLONE\", not an xArm board"))
      << r.err;
}

TEST_F(HidCli, ListShowsTheBoardAndTheUsbCheck) {
  const Outcome r = run({"list", "--json"}, {{"ARMCTL_FAKE_HID_NODE", node_}});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["hid_boards"].size(), 1u) << r.out;
  EXPECT_EQ(j["hid_boards"][0]["path"], node_);
  EXPECT_TRUE(j["usb_boards_without_hidraw"].is_array()) << r.out;
}

}  // namespace
