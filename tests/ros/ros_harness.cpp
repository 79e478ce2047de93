#include "ros_harness.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <ros/ros.h>

extern char** environ;

namespace armctl::ros_test {

Process::Process(const std::vector<std::string>& argv, const std::string& log) : log_(log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  posix_spawn_file_actions_addclose(&actions, 0);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  // Its own process group, so that kill_now also ends what it started (roscore's rosmaster
  // and rosout) instead of leaving them on the port.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  const int r = posix_spawnp(&pid_, args[0], &actions, &attributes, args.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  if (r != 0) throw std::runtime_error("cannot start " + argv[0]);
}

Process::~Process() { terminate(); }

std::optional<int> Process::wait_exit(std::chrono::milliseconds timeout) {
  if (status_) return status_;
  const auto end = std::chrono::steady_clock::now() + timeout;
  do {
    int st = 0;
    if (waitpid(pid_, &st, WNOHANG) == pid_) {
      status_ = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
      return status_;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  } while (std::chrono::steady_clock::now() < end);
  return std::nullopt;
}

namespace {

// Until no process of group `group` is left (roscore's rosmaster and rosout outlive the
// roscore process by a moment): a master restarted before would find the port taken.
bool group_gone(int group, std::chrono::milliseconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (::kill(-group, 0) == 0) {
    if (std::chrono::steady_clock::now() >= end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

}  // namespace

void Process::terminate() {
  if (pid_ <= 0) return;
  if (!status_) {
    ::kill(pid_, SIGTERM);
    if (!wait_exit(std::chrono::seconds(10))) return kill_now();
  }
  if (!group_gone(pid_, std::chrono::seconds(10))) kill_now();
}

void Process::kill_now() {
  if (pid_ <= 0) return;
  ::kill(-pid_, SIGKILL);
  if (!status_) wait_exit(std::chrono::seconds(10));
  group_gone(pid_, std::chrono::seconds(10));
}

std::string Process::log_text() const {
  std::ifstream in(log_);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

namespace {

int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  socklen_t len = sizeof a;
  if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0)
    throw std::runtime_error("no free loopback port");
  const int port = ntohs(a.sin_port);
  ::close(fd);
  return port;
}

}  // namespace

const RosWorld& ros_world() {
  static std::once_flag once;
  static RosWorld world;
  std::call_once(once, [] {
    char tmpl[] = "/tmp/armctl-ros-test-XXXXXX";
    if (!mkdtemp(tmpl)) throw std::runtime_error("mkdtemp failed");
    world.dir = tmpl;
    // Gone when the test process ends (its children are ended by then).
    std::atexit([] { std::filesystem::remove_all(world.dir); });
    world.port = free_port();
    world.master_uri = "http://127.0.0.1:" + std::to_string(world.port);
    // Every process started from here (the master, the node) inherits these: loopback only.
    setenv("ROS_MASTER_URI", world.master_uri.c_str(), 1);
    setenv("ROS_IP", "127.0.0.1", 1);
    unsetenv("ROS_HOSTNAME");
    setenv("ROS_HOME", world.dir.c_str(), 1);
    setenv("ROS_LOG_DIR", (world.dir + "/log").c_str(), 1);
    setenv("ARMCTL_CONFIG_DIR", ARMCTL_SOURCE_DIR "/config", 1);
    int argc = 1;
    char name[] = "armctl_ros_test";
    char* argv[] = {name, nullptr};
    ros::init(argc, argv, "armctl_ros_test", ros::init_options::AnonymousName | ros::init_options::NoSigintHandler);
  });
  return world;
}

bool wait_until(const std::function<bool()>& condition, std::chrono::milliseconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (!condition()) {
    if (std::chrono::steady_clock::now() >= end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

std::unique_ptr<Process> start_master() {
  const auto& w = ros_world();
  auto p = std::make_unique<Process>(
      std::vector<std::string>{"roscore", "-p", std::to_string(w.port)}, w.dir + "/roscore.log");
  // Answered by this roscore, not by one that is still going away.
  Process* started = p.get();
  if (!wait_until([started] { return !started->wait_exit(std::chrono::milliseconds(0)) && ros::master::check(); },
                  std::chrono::seconds(30)) ||
      p->wait_exit(std::chrono::milliseconds(0)))
    throw std::runtime_error("roscore did not answer on " + w.master_uri + ": " + p->log_text());
  return p;
}

}  // namespace armctl::ros_test
