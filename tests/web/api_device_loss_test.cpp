// The API when the device goes away: the SCARA's simulator in its own process (as
// `armctl sim scara --listen` serves it), killed while the server runs. The state says the
// link is lost, a move is answered with the device's error, and the server keeps serving;
// restarted, the simulator is found again.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

#include "api_server.hpp"

namespace armctl::web::testing {
namespace {

class SimProcess {
 public:
  explicit SimProcess(const std::string& socket) {
    pid_ = ::fork();
    if (pid_ == 0) {
      const std::string log = socket + ".log";
      std::FILE* out = std::freopen(log.c_str(), "w", stdout);
      (void)out;
      ::dup2(STDOUT_FILENO, STDERR_FILENO);
      ::execl(ARMCTL_BINARY_DIR "/armctl", "armctl", "sim", "scara", "--listen", socket.c_str(),
              static_cast<char*>(nullptr));
      ::_exit(127);
    }
  }
  ~SimProcess() { kill(); }
  void kill() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }

 private:
  pid_t pid_ = -1;
};

TEST(WebDeviceLoss, TheStateSaysTheLinkIsLostAMoveGetsTheDevicesErrorAndARestartedArmIsFoundAgain) {
  const auto dir = std::filesystem::temp_directory_path() / ("armctl-web-loss-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string socket = (dir / "scara.sock").string();
  SimProcess sim(socket);
  for (int i = 0; i < 600 && !std::filesystem::exists(socket); ++i) ::usleep(50 * 1000);  // poll, not settle
  ASSERT_TRUE(std::filesystem::exists(socket)) << "armctl sim scara did not listen on " << socket;
  {
    ApiServer api("scara", {}, "unix:" + socket);
    api.first_positions();
    api.take("page");
    Reply state = api.get("/api/v1/state", "page");
    ASSERT_EQ(state.status, 200);
    EXPECT_EQ(state.body["link"]["ok"], true);

    sim.kill();
    ASSERT_TRUE(api.wait_until([](const session::ArmSnapshot& s) { return !s.link_ok; }));
    state = api.get("/api/v1/state", "page");
    ASSERT_EQ(state.status, 200) << state.text;
    EXPECT_EQ(state.body["link"]["ok"], false);
    EXPECT_NE(state.body["link"]["error"].get<std::string>().find("closed the connection"), std::string::npos)
        << state.text;

    const Reply move = api.post("/api/v1/joints", {{"positions", {{"SHOULDER", 10.0}}}}, "page");
    EXPECT_EQ(move.status, 500) << move.text;
    ASSERT_TRUE(move.body.is_object()) << move.text;
    EXPECT_NE(move.body["error"].get<std::string>().find("closed the connection"), std::string::npos) << move.text;
    // Still serving: the page, and STOP, which says that it may not have reached the arm.
    EXPECT_EQ(api.get("/", "page").status, 200);
    const Reply stop = api.post("/api/v1/stop", json::object(), "page");
    ASSERT_EQ(stop.status, 200) << stop.text;
    EXPECT_EQ(stop.body["stopped"], true);
    EXPECT_EQ(stop.body["link_ok"], false);
    EXPECT_NE(stop.body["warning"].get<std::string>().find("may not have reached it"), std::string::npos) << stop.text;

    // The simulator comes back on the same socket: the server opens the link again by
    // itself (no restart of serve), and the arm moves again.
    EXPECT_EQ(state.body["link"]["reconnects"], true);
    SimProcess again(socket);
    ASSERT_TRUE(api.wait_until([](const session::ArmSnapshot& s) { return s.link_ok; }, 30s))
        << api.worker().snapshot().link_error;
    state = api.get("/api/v1/state", "page");
    EXPECT_EQ(state.body["link"]["ok"], true) << state.text;
    const Reply moved = api.post("/api/v1/joints", {{"positions", {{"SHOULDER", 5.0}}}, {"speed", 0.5}}, "page");
    EXPECT_EQ(moved.status, 200) << moved.text;
    EXPECT_TRUE(api.wait_idle(30s));
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace armctl::web::testing
