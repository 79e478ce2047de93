// `armctl xarm` end to end: the real binary (ARMCTL_BINARY_DIR/armctl) against (a) its
// embedded emulated xArm, whose stored state lives in $ARMCTL_STATE_DIR (a temp dir here),
// and (b) a separate `armctl sim xarm` process reached through its --link symlink.
// Checks output, --json documents, exit status, and the messages for bad arguments.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <poll.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "run_armctl.hpp"

namespace {

namespace fs = std::filesystem;

const std::string kArmctl = std::string(ARMCTL_BINARY_DIR) + "/armctl";

struct Outcome {
  int status = -1;  // exit status; -1 if killed by a signal
  std::string out;
  std::string err;
};

// A started armctl process with its stdout and stderr on pipes.
class Process {
 public:
  Process(const std::vector<std::string>& args, const std::string& state_dir) {
    int out[2], err[2];
    if (::pipe2(out, O_CLOEXEC) != 0 || ::pipe2(err, O_CLOEXEC) != 0) std::abort();
    pid_ = ::fork();
    if (pid_ < 0) std::abort();
    if (pid_ == 0) {
      ::dup2(out[1], 1);
      ::dup2(err[1], 2);
      ::setenv("ARMCTL_STATE_DIR", state_dir.c_str(), 1);
      std::vector<char*> argv{const_cast<char*>(kArmctl.c_str())};
      for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      ::execv(kArmctl.c_str(), argv.data());
      ::_exit(127);
    }
    ::close(out[1]);
    ::close(err[1]);
    out_ = out[0];
    err_ = err[0];
  }
  ~Process() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    if (out_ >= 0) ::close(out_);
    if (err_ >= 0) ::close(err_);
  }
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;

  pid_t pid() const { return pid_; }

  // Reads stdout until a whole line has arrived (blocking on the pipe: no sleeps, no
  // polling loop); nothing if stdout closed first.
  std::optional<std::string> read_line() {
    for (;;) {
      if (auto nl = out_text_.find('\n', line_pos_); nl != std::string::npos) {
        std::string line = out_text_.substr(line_pos_, nl - line_pos_);
        line_pos_ = nl + 1;
        return line;
      }
      if (!read_some(out_, out_text_)) return std::nullopt;
    }
  }

  // Reads both pipes to the end, waits for the exit and returns everything.
  Outcome finish() {
    pollfd fds[2] = {{out_, POLLIN, 0}, {err_, POLLIN, 0}};
    bool open[2] = {true, true};
    while (open[0] || open[1]) {
      for (int i = 0; i < 2; ++i) fds[i].fd = open[i] ? (i == 0 ? out_ : err_) : -1;
      if (::poll(fds, 2, -1) < 0 && errno != EINTR) break;
      if (open[0] && (fds[0].revents & (POLLIN | POLLHUP))) open[0] = read_some(out_, out_text_);
      if (open[1] && (fds[1].revents & (POLLIN | POLLHUP))) open[1] = read_some(err_, err_text_);
    }
    int st = 0;
    ::waitpid(pid_, &st, 0);
    pid_ = -1;
    return Outcome{WIFEXITED(st) ? WEXITSTATUS(st) : -1, out_text_, err_text_};
  }

 private:
  static bool read_some(int fd, std::string& into) { return armctl::cli_test::read_some(fd, into); }

  pid_t pid_ = -1;
  int out_ = -1;
  int err_ = -1;
  std::string out_text_;
  std::string err_text_;
  std::size_t line_pos_ = 0;
};

using armctl::cli_test::contains;
using armctl::cli_test::json_lines;
using armctl::cli_test::split_args;

class XarmCli : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "armctl-xarm-cli-XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
    state_ = (dir_ / "state").string();
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  // `armctl xarm ARGS` (ARGS split at spaces) with ARMCTL_STATE_DIR = our temp dir.
  Outcome xarm(const std::string& args) {
    auto argv = split_args(args);
    argv.insert(argv.begin(), "xarm");
    return Process(argv, state_).finish();
  }
  std::string write_file(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }

  fs::path dir_;
  std::string state_;
};

const char* kWave =
    "# two servos, three actions\n"
    "servos 2\n"
    "100 1=400 2=30deg\n"
    "100 1=600 2=keep\n"
    "50  2=500 1=500\n";

// ------------------------------------------------------------------ embedded board

TEST_F(XarmCli, MoveWithWaitReachesTheTargetsInDegreesAndUnits) {
  const Outcome r = xarm("move 1=30deg 2=300 6=keep --time 200 --wait");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_TRUE(contains(r.out, "servo 1:  625 (+30.0 deg)")) << r.out;  // 500 + 30 x 1000/240
  EXPECT_TRUE(contains(r.out, "servo 2:  300")) << r.out;
  EXPECT_TRUE(contains(r.out, "servo 6:  500")) << r.out;  // keep: left where it was
}

// The board stretches a 0 ms move to its servos' speed limit (500 units at 1500 units/s):
// --wait reads the servos back until they are there, instead of sleeping for --time.
TEST_F(XarmCli, MoveWithWaitWaitsForAStretchedMove) {
  const Outcome r = xarm("--json move 1=0 2=1000 --time 0 --wait --tolerance 2");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  const auto docs = json_lines(r.out);
  ASSERT_EQ(docs.size(), 1u) << r.out;
  ASSERT_EQ(docs[0]["positions"].size(), 2u);
  EXPECT_LE(docs[0]["positions"][0]["position"].get<int>(), 2) << r.out;
  EXPECT_GE(docs[0]["positions"][1]["position"].get<int>(), 998) << r.out;
}

// A move the board refuses (servo 1's limits end at 600) leaves the servo where it was:
// --wait says which servo did not arrive, where it is and where it was sent, and fails.
TEST_F(XarmCli, MoveWithWaitNamesEveryServoThatDidNotArrive) {
  ASSERT_EQ(xarm("info write --id 1 --position-min 0 --position-max 600").status, 0);
  const Outcome r = xarm("move 1=900 3=700 --time 100 --wait --wait-timeout 300");
  EXPECT_NE(r.status, 0) << r.out;
  EXPECT_TRUE(contains(r.out, "servo 1:  500")) << r.out;
  EXPECT_TRUE(contains(r.err, "2 of 2 servos did not arrive")) << r.err;
  EXPECT_TRUE(contains(r.err, "servo 1 at 500 (target 900)")) << r.err;
  EXPECT_TRUE(contains(r.err, "servo 3 at 500 (target 700)")) << r.err;
}

TEST_F(XarmCli, JsonOutputParses) {
  const Outcome b = xarm("--json battery");
  ASSERT_EQ(b.status, 0) << b.err;
  auto docs = json_lines(b.out);
  ASSERT_EQ(docs.size(), 1u) << b.out;
  EXPECT_EQ(docs[0]["millivolts"], 7500);

  const Outcome m = xarm("--json move 3=-15deg --time 100 --wait");
  ASSERT_EQ(m.status, 0) << m.err;
  docs = json_lines(m.out);
  ASSERT_EQ(docs.size(), 1u) << m.out;
  ASSERT_EQ(docs[0]["positions"].size(), 1u);
  EXPECT_EQ(docs[0]["positions"][0]["servo"], 3);
  EXPECT_EQ(docs[0]["positions"][0]["position"], 438);  // 500 - 15 x 1000/240 = 437.5 -> 438
  EXPECT_NEAR(docs[0]["positions"][0]["degrees"].get<double>(), -15.0, 0.2);

  const Outcome p = xarm("positions --json 1 2");  // --json after the subcommand works too
  ASSERT_EQ(p.status, 0) << p.err;
  docs = json_lines(p.out);
  ASSERT_EQ(docs.size(), 1u);
  ASSERT_EQ(docs[0]["positions"].size(), 2u);

  const Outcome i = xarm("--json info read");
  ASSERT_EQ(i.status, 0) << i.err;
  docs = json_lines(i.out);
  ASSERT_EQ(docs.size(), 1u);
  EXPECT_EQ(docs[0]["position_max"], 1000);
  EXPECT_EQ(docs[0]["temp"], 35);

  const Outcome o = xarm("--json offset read 4");
  ASSERT_EQ(o.status, 0) << o.err;
  docs = json_lines(o.out);
  ASSERT_EQ(docs.size(), 1u);
  EXPECT_EQ(docs[0]["offsets"][0]["servo"], 4);
  EXPECT_EQ(docs[0]["offsets"][0]["offset"], 0);

  const Outcome off = xarm("--json off 1 2");
  ASSERT_EQ(off.status, 0) << off.err;
  docs = json_lines(off.out);
  ASSERT_EQ(docs.size(), 1u);
  EXPECT_TRUE(docs[0]["ok"].get<bool>());
}

TEST_F(XarmCli, EveryCommandRunsOnTheEmbeddedBoard) {
  const std::string wave = write_file("wave.grp", kWave);
  for (const std::string& args : std::vector<std::string>{"battery", "positions", "positions 2 5", "off", "off 3", "move 1=500 2=250 --time 0",
        "offset read", "offset adjust 2 -30", "offset save 2", "mode 2 motor --speed 700",
        "mode 2 motor --speed=-1000", "mode 2 servo", "info read",
        "info write --id 1 --temp-max 80", "group download " + wave + " --group 7",
        "group run 7", "group stop", "group speed 7 150", "group speed all 100",
        "group erase 7", "group erase all"}) {
    const Outcome r = xarm(args);
    EXPECT_EQ(r.status, 0) << args << "\n" << r.out << r.err;
  }
}

TEST_F(XarmCli, EmbeddedBoardKeepsGroupsOffsetsAndLimitsButNotPositions) {
  const std::string wave = write_file("wave.grp", kWave);
  // A group downloaded by one command runs in the next one.
  const Outcome d = xarm("group download " + wave + " --group 3");
  ASSERT_EQ(d.status, 0) << d.err;
  EXPECT_TRUE(contains(d.out, "group 3: 3 actions downloaded")) << d.out;
  EXPECT_TRUE(fs::exists(fs::path(state_) / "xarm-emulator" / "group-003.grp"));

  const Outcome run = xarm("--json group run 3 --times 2 --wait");
  ASSERT_EQ(run.status, 0) << run.out << run.err;
  auto docs = json_lines(run.out);
  ASSERT_EQ(docs.size(), 3u) << run.out;  // done, started, finished
  EXPECT_EQ(docs[1]["event"], "started");
  EXPECT_EQ(docs[1]["group"], 3);
  EXPECT_EQ(docs[1]["count"], 2);
  EXPECT_EQ(docs[2]["event"], "finished");
  EXPECT_EQ(docs[2]["group"], 3);

  // Speed is volatile on the board (100 % after a restart); the command itself is accepted.
  EXPECT_EQ(xarm("group speed 3 200").status, 0);

  // Erased in one command: gone for the next.
  ASSERT_EQ(xarm("group erase 3").status, 0);
  const Outcome gone = xarm("group run 3 --wait");
  EXPECT_NE(gone.status, 0);
  EXPECT_TRUE(contains(gone.err, "is group 3 empty")) << gone.err;

  // Saved limits persist (like a servo's EEPROM).
  ASSERT_EQ(xarm("info write --id 1 --position-min 100 --position-max 900").status, 0);
  docs = json_lines(xarm("--json info read").out);
  ASSERT_EQ(docs.size(), 1u);
  EXPECT_EQ(docs[0]["position_min"], 100);
  EXPECT_EQ(docs[0]["position_max"], 900);

  // An adjusted offset is volatile (a new command is a power cycle) ...
  ASSERT_EQ(xarm("offset adjust 4 -20").status, 0);
  EXPECT_TRUE(contains(xarm("offset read 4").out, "servo 4: offset +0"));

  // ... and positions always start at centre.
  ASSERT_EQ(xarm("move 5=900 --time 0 --wait").status, 0);
  EXPECT_TRUE(contains(xarm("positions 5").out, "servo 5:  500"));
}

TEST_F(XarmCli, DeviceSimIsTheEmbeddedBoard) {
  const std::string wave = write_file("wave.grp", kWave);
  ASSERT_EQ(xarm("group download " + wave + " --group 4").status, 0);
  const Outcome run = xarm("--device sim group run 4 --wait");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_TRUE(contains(run.out, "finished")) << run.out;
  const Outcome bad = xarm("--device sim?speed=3 battery");
  EXPECT_NE(bad.status, 0);
  EXPECT_TRUE(contains(bad.err, "unknown option 'speed' (this device takes: miscal)")) << bad.err;
  EXPECT_TRUE(contains(bad.err, "allowed: sim, sim?miscal=SEED, hid")) << bad.err;
}

TEST_F(XarmCli, WatchRunsUntilSigint) {
  Process watch({"xarm", "watch", "--interval", "20"}, state_);
  for (int i = 0; i < 3; ++i) {
    auto line = watch.read_line();
    ASSERT_TRUE(line) << "watch ended early";
    EXPECT_TRUE(contains(*line, "1=500")) << *line;
    EXPECT_TRUE(contains(*line, "6=500")) << *line;
  }
  ASSERT_EQ(::kill(watch.pid(), SIGINT), 0);
  const Outcome r = watch.finish();
  EXPECT_EQ(r.status, 0) << r.err;
}

TEST_F(XarmCli, BadArgumentsGetAClearMessageAndNonZeroStatus) {
  const std::string bad_group = write_file("bad.grp", "servos 2\n100 1=500 2=500\n100 1=500 2=abc\n");
  const std::string mixed = write_file("mixed.grp", "100 1=500 2=500\n100 1=500\n");
  const std::string fifo = (dir_ / "fifo.grp").string();  // no writer: reading it blocked for ever
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"move 7=500", "servo 7 is out of range (allowed 1..6)"},
      {"positions 0", "servo 0 is out of range (allowed 1..6)"},
      {"move 1=1001", "servo 1 position 1001 is out of range (allowed 0..1000)"},
      {"move 1=130deg", "-120deg..120deg"},
      {"move 1", "SERVO=POSITION"},
      {"--device bogus:thing battery", "bogus:thing"},
      {"--device serial:/dev/armctl-no-such-port battery", "/dev/armctl-no-such-port"},
      {"group download " + bad_group, bad_group + ":3:"},
      {"group download " + mixed, mixed + ":2:"},
      {"group download " + (dir_ / "missing.grp").string(), "missing.grp"},
      {"group run 255", "group 255 is out of range (allowed 0..254)"},
      {"group erase 300", "allowed 0..254"},
      {"group erase 255", "group (0..254 or all) 255 is out of range"},  // "all" is the word
      {"group speed 255 50", "group (0..254 or all) 255 is out of range"},
      {"mode 1 motor", "mode motor needs --speed"},
      {"group speed 1 0", "speed percentage 0 is out of range (allowed 1..1000)"},
      {"offset adjust 1 200", "offset 200 is out of range (allowed -125..125)"},
      {"mode 1 motor --speed 5000", "--speed 5000 is out of range (allowed -1000..1000)"},
      {"mode 1 turbo", "servo or motor"},
      {"frobnicate", "unknown command 'frobnicate'; allowed: move"},
      // Numeric options name the option, the value and the range (not "Could not convert").
      {"info write --id 300", "--id: 300 is outside 1..19"},
      {"info write --id -1", "--id: -1 is outside 1..19"},
      {"info write --id 1 --position-max 70000", "--position-max: 70000 is outside 0..1000"},
      {"info write --id 1 --millivolts-min 99", "--millivolts-min: 99 is outside 4500..12000"},
      {"info write --id 1 --led-warning 8", "--led-warning: 8 is outside 0..7"},
      {"--timeout abc positions", "--timeout: 'abc' is not a whole number (allowed 1..60000)"},
      {"--servos 99999999999999999999 positions", "--servos: 99999999999999999999 is outside 1..19"},
      {"move 1=500 --time -5", "--time: -5 is outside 0..30000"},
      {"group run 1 --times 70000", "--times: 70000 is outside 0..65535"},
      {"watch --interval 5", "--interval: 5 is outside 10..60000"},
      // A directory or a FIFO as a group file is refused at once, naming the path.
      {"group download " + dir_.string(), "group file " + dir_.string() + " is not a regular file (a directory)"},
      {"group download " + fifo, "group file " + fifo + " is not a regular file (a FIFO)"},
  };
  for (const auto& [args, want] : cases) {
    const Outcome r = xarm(args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_TRUE(contains(r.out + r.err, want)) << args << "\n" << r.out << r.err;
  }
  // Nothing was downloaded by the refused files.
  EXPECT_FALSE(fs::exists(fs::path(state_) / "xarm-emulator" / "group-000.grp"));
}

// A board that cannot store (here: a file-size limit, which also works as root where a
// read-only dir would not) refuses; the host says so instead of "saved", and nothing dies of
// SIGXFSZ.
TEST_F(XarmCli, ABoardThatCannotStoreSaysSoAndTheCommandFails) {
  auto run = [&](const std::string& args) {  // through a shell: ulimit -f 0 for armctl only
    const std::string cmd = "ulimit -f 0; ARMCTL_STATE_DIR='" + state_ + "' exec " + kArmctl + " xarm " + args + " 2>&1";
    FILE* p = ::popen(cmd.c_str(), "r");
    std::string out;
    char buf[4096];
    while (std::size_t n = std::fread(buf, 1, sizeof buf, p)) out.append(buf, n);
    const int st = ::pclose(p);
    return Outcome{WIFEXITED(st) ? WEXITSTATUS(st) : -1, out, ""};
  };
  Outcome r = run("offset save");
  EXPECT_EQ(r.status, 1) << r.out;  // was killed by SIGXFSZ
  EXPECT_TRUE(contains(r.out, "ServoOffsetWrite: the board refused it")) << r.out;
  EXPECT_TRUE(contains(r.out, "could not be stored")) << r.out;
  EXPECT_FALSE(contains(r.out, "offsets saved")) << r.out;

  const std::string wave = write_file("wave.grp", kWave);
  r = run("group download " + wave + " --group 3");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_TRUE(contains(r.out, "the board may have refused it")) << r.out;
  EXPECT_TRUE(contains(r.out, "the board logged: GroupDownload: cannot store group 3")) << r.out;
  EXPECT_FALSE(fs::exists(fs::path(state_) / "xarm-emulator" / "group-003.grp"));
}

// Terminal control sequences in a group file's name and fields reach the terminal escaped.
TEST_F(XarmCli, ControlCharactersFromAGroupFileAreEscapedInMessages) {
  const std::string title = "\x1b]0;owned\x07";
  const std::string field = write_file("field.grp", "servos 1\n100 1=5" + title + "00\n");
  Outcome r = xarm("group download " + field);
  EXPECT_NE(r.status, 0);
  EXPECT_TRUE(contains(r.err, "'1=5\\x1b]0;owned\\x0700'")) << r.err;
  EXPECT_FALSE(contains(r.out + r.err, "\x1b")) << r.err;

  const std::string name = (dir_ / ("a" + title + ".grp")).string();  // no such file
  r = Process({"xarm", "group", "download", name}, state_).finish();
  EXPECT_NE(r.status, 0);
  EXPECT_TRUE(contains(r.err, "a\\x1b]0;owned\\x07.grp: no such file")) << r.err;
  EXPECT_FALSE(contains(r.out + r.err, "\x1b")) << r.err;

  // An unexpected argument echoed back by the parser is escaped too.
  r = Process({"xarm", "positions", "1", "--bogus" + title}, state_).finish();
  EXPECT_NE(r.status, 0);
  EXPECT_FALSE(contains(r.out + r.err, "\x1b")) << r.err;
  EXPECT_TRUE(contains(r.err, "\\x1b]0;owned")) << r.err;
}

// ------------------------------------------------- `armctl controller` as a process

// The arm controller refuses a move naming a joint that does not answer (joint 3 is dead
// here), and no joint moves; `move --wait` sees that the servos did not arrive and says so.
TEST_F(XarmCli, ThroughTheArmControllerARefusedMoveFailsTheWait) {
  const std::string link = (dir_ / "scara").string();
  Process controller({"controller", "--bus", "sim?dead=3", "--link", link}, state_);
  std::optional<std::string> line;
  while ((line = controller.read_line()) && line->rfind("/dev/pts/", 0) != 0) {
  }
  ASSERT_TRUE(line) << "armctl controller ended before printing its pty";

  const std::string dev = "--device serial:" + link + " --servos 7 ";
  const Outcome refused = xarm(dev + "move 2=600 3=600 --time 200 --wait --wait-timeout 300");
  EXPECT_NE(refused.status, 0) << refused.out;
  EXPECT_TRUE(contains(refused.err, "2 of 2 servos did not arrive")) << refused.err;
  EXPECT_TRUE(contains(refused.err, "servo 2 at 500 (target 600)")) << refused.err;
  EXPECT_TRUE(contains(refused.err, "servo 3 at 500 (target 600)")) << refused.err;

  // A move of joints that answer still works and is waited for.
  const Outcome moved = xarm(dev + "--json move 2=600 --time 300 --wait");
  ASSERT_EQ(moved.status, 0) << moved.err;
  const auto docs = json_lines(moved.out);
  ASSERT_EQ(docs.size(), 1u) << moved.out;
  EXPECT_NEAR(docs[0]["positions"][0]["position"].get<int>(), 600, 10) << moved.out;

  ASSERT_EQ(::kill(controller.pid(), SIGTERM), 0);
  const Outcome end = controller.finish();
  EXPECT_TRUE(contains(end.out + end.err, "MultiServoMove refused: joint 3 (UAE) is not answering"))
      << end.out << end.err;
}

// Under --json a server's whole output is JSON lines on stdout: "started" with the pty path
// a host opens, every log line as "log", and "stopped" with its counts; nothing on stderr.
TEST_F(XarmCli, ServersLogAsJsonLinesUnderJson) {
  const std::string link = (dir_ / "scara").string();
  Process controller({"controller", "--json", "--bus", "sim?dead=3", "--link", link}, state_);
  // Log lines may come first (what the controller found on the bus while it started).
  std::optional<std::string> first;
  nlohmann::json started;
  while ((first = controller.read_line()) && (started = nlohmann::json::parse(*first))["event"] == "log") {
  }
  ASSERT_TRUE(first) << "armctl controller --json ended before it started";
  EXPECT_EQ(started["event"], "started") << *first;
  EXPECT_EQ(started["source"], "controller") << *first;
  EXPECT_EQ(started["joints"], 7) << *first;
  EXPECT_EQ(started["device"].get<std::string>().rfind("/dev/pts/", 0), 0u) << *first;

  const Outcome refused = xarm("--device serial:" + link + " --servos 7 move 3=600 --time 200");
  EXPECT_EQ(refused.status, 0) << refused.err;  // sent; the controller refuses it in its log
  ASSERT_EQ(::kill(controller.pid(), SIGTERM), 0);
  const Outcome end = controller.finish();
  EXPECT_EQ(end.err, "");
  const auto docs = json_lines(end.out);  // throws on a line that is not JSON
  bool dead_joint_logged = false, refusal_logged = false;
  for (const auto& d : docs) {
    if (d["event"] != "log") continue;
    const std::string m = d["message"];
    dead_joint_logged |= contains(m, "joint 3 UAE: NOT ANSWERING");
    refusal_logged |= contains(m, "MultiServoMove refused: joint 3 (UAE) is not answering");
  }
  EXPECT_TRUE(dead_joint_logged) << end.out;
  EXPECT_TRUE(refusal_logged) << end.out;
  ASSERT_FALSE(docs.empty());
  EXPECT_EQ(docs.back()["event"], "stopped") << end.out;
  EXPECT_EQ(docs.back()["refused_moves"], 1) << end.out;

  Process emulator({"sim", "xarm", "--json"}, state_);
  first = emulator.read_line();
  ASSERT_TRUE(first);
  const auto xarm_started = nlohmann::json::parse(*first);
  EXPECT_EQ(xarm_started["event"], "started") << *first;
  EXPECT_EQ(xarm_started["source"], "sim xarm") << *first;
  const std::string device = xarm_started["device"];
  EXPECT_EQ(xarm("--device serial:" + device + " battery").status, 0);
  ASSERT_EQ(::kill(emulator.pid(), SIGINT), 0);
  const Outcome xarm_end = emulator.finish();
  EXPECT_EQ(xarm_end.status, 0);
  EXPECT_EQ(xarm_end.err, "");
  const auto xarm_docs = json_lines(xarm_end.out);
  ASSERT_FALSE(xarm_docs.empty());
  EXPECT_EQ(xarm_docs.back()["event"], "stopped") << xarm_end.out;
  EXPECT_GE(xarm_docs.back()["handled"].get<int>(), 1) << xarm_end.out;
}

// ------------------------------------------------- `armctl sim xarm` as a process

TEST_F(XarmCli, AgainstASimXarmProcess) {
  const std::string link = (dir_ / "xarm").string();
  const std::string board_state = (dir_ / "board").string();
  auto emulator = std::make_unique<Process>(
      std::vector<std::string>{"sim", "xarm", "--link", link, "--state-dir", board_state},
      state_);
  // Ready once it prints the pty path (it creates the link before printing).
  auto pty = emulator->read_line();
  ASSERT_TRUE(pty) << "armctl sim xarm ended before printing its pty";
  EXPECT_EQ(pty->rfind("/dev/pts/", 0), 0u) << *pty;
  ASSERT_EQ(fs::read_symlink(link).string(), *pty);

  const std::string dev = "--device " + link + " ";
  // Positions persist between commands here: one board for all of them.
  const Outcome m = xarm(dev + "move 1=30deg 2=300 --time 150 --wait");
  ASSERT_EQ(m.status, 0) << m.err;
  EXPECT_TRUE(contains(m.out, "servo 1:  625")) << m.out;
  EXPECT_TRUE(contains(xarm(dev + "positions 1 2").out, "servo 2:  300"));

  auto docs = json_lines(xarm(dev + "--json battery").out);
  ASSERT_EQ(docs.size(), 1u);
  EXPECT_EQ(docs[0]["millivolts"], 7500);

  // Offsets: adjust acts at once and survives between commands on a live board; save.
  ASSERT_EQ(xarm(dev + "offset adjust 3 -20").status, 0);
  EXPECT_TRUE(contains(xarm(dev + "offset read 3").out, "servo 3: offset -20"));
  ASSERT_EQ(xarm(dev + "offset save 3").status, 0);

  EXPECT_EQ(xarm(dev + "off 1").status, 0);
  EXPECT_EQ(xarm(dev + "mode 4 motor --speed=-500").status, 0);
  EXPECT_EQ(xarm(dev + "mode 4 servo").status, 0);
  EXPECT_EQ(xarm(dev + "info write --id 1 --temp-max 70").status, 0);
  docs = json_lines(xarm(dev + "--json info read").out);
  ASSERT_EQ(docs.size(), 1u);
  EXPECT_EQ(docs[0]["temp_max"], 70);

  // Groups: download, run to the end, run continuously and stop, speed, erase.
  const std::string wave = write_file("wave.grp", kWave);
  ASSERT_EQ(xarm(dev + "group download " + wave + " --group 5").status, 0);
  const Outcome run = xarm(dev + "group run 5 --wait");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_TRUE(contains(run.out, "started")) << run.out;
  EXPECT_TRUE(contains(run.out, "finished")) << run.out;
  ASSERT_EQ(xarm(dev + "group speed 5 300").status, 0);
  const Outcome forever = xarm(dev + "group run 5 --times 0");
  ASSERT_EQ(forever.status, 0) << forever.err;
  EXPECT_TRUE(contains(forever.out, "started")) << forever.out;
  const Outcome stop = xarm(dev + "--json group stop");
  ASSERT_EQ(stop.status, 0) << stop.err;
  docs = json_lines(stop.out);
  ASSERT_FALSE(docs.empty());
  EXPECT_EQ(docs.front()["event"], "stopped") << stop.out;
  // In text, the board's event says it once (it was printed twice).
  ASSERT_EQ(xarm(dev + "group run 5 --times 0").status, 0);
  const Outcome stop_text = xarm(dev + "group stop");
  ASSERT_EQ(stop_text.status, 0) << stop_text.err;
  EXPECT_EQ(stop_text.out.find("stopped"), stop_text.out.rfind("stopped")) << stop_text.out;
  ASSERT_EQ(xarm(dev + "group erase all").status, 0);
  EXPECT_NE(xarm(dev + "group run 5 --wait").status, 0);

  // A watch on the live board, ended by SIGINT.
  {
    Process watch({"xarm", "--device", link, "watch", "--interval", "20"}, state_);
    ASSERT_TRUE(watch.read_line());
    ASSERT_EQ(::kill(watch.pid(), SIGINT), 0);
    EXPECT_EQ(watch.finish().status, 0);
  }

  ASSERT_EQ(::kill(emulator->pid(), SIGTERM), 0);
  const Outcome end = emulator->finish();
  EXPECT_EQ(end.status, 0) << end.err;
  EXPECT_FALSE(fs::exists(fs::symlink_status(link))) << "link left behind";
  EXPECT_TRUE(contains(end.err, "stopped;")) << end.err;

  // The saved offset is on the board's state dir: a new board process starts with it. This one
  // is started by the old name, `emulate xarm`, which still works and says it is deprecated.
  emulator = std::make_unique<Process>(
      std::vector<std::string>{"emulate", "xarm", "--link", link, "--state-dir", board_state},
      state_);
  ASSERT_TRUE(emulator->read_line());
  EXPECT_TRUE(contains(xarm(dev + "offset read 3").out, "servo 3: offset -20"));
  ASSERT_EQ(::kill(emulator->pid(), SIGTERM), 0);
  const Outcome old_name = emulator->finish();
  EXPECT_EQ(old_name.status, 0) << old_name.err;
  EXPECT_TRUE(contains(old_name.err, "'emulate xarm' is deprecated, use 'armctl sim xarm'")) << old_name.err;
}

}  // namespace
