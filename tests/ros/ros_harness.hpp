// What the ROS node tests need around them: processes they start and stop themselves (a
// roscore on a free loopback port, the node, robot_state_publisher, a simulator), with
// ROS_HOME and ROS_LOG_DIR in a temporary folder, and waiting for conditions with a
// timeout (never a sleep to let things settle). C++17: it includes ROS headers.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace armctl::ros_test {

// A child process in its own process group; its stdout and stderr go to `log`. Ended
// (SIGTERM, then SIGKILL to the group) when destroyed.
class Process {
 public:
  Process(const std::vector<std::string>& argv, const std::string& log);
  ~Process();
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;

  // The exit status once it has ended (within `timeout`), or nothing.
  std::optional<int> wait_exit(std::chrono::milliseconds timeout);
  void terminate();  // SIGTERM, waits up to 10 s, then SIGKILL
  void kill_now();   // SIGKILL: a device that goes away
  std::string log_text() const;
  int pid() const { return pid_; }

 private:
  int pid_ = -1;
  std::optional<int> status_;
  std::string log_;
};

// The folder, port and environment of one test process's ROS world (set up once).
struct RosWorld {
  std::string dir;   // ROS_HOME; logs under it
  int port = 0;
  std::string master_uri;
};
const RosWorld& ros_world();  // also initialises roscpp in this process (once)

// roscore (the master and rosout, as a user starts them) on ros_world().port; waits until
// the master answers.
std::unique_ptr<Process> start_master();

// Polls `condition` (every 20 ms) until it holds or `timeout` passes.
bool wait_until(const std::function<bool()>& condition, std::chrono::milliseconds timeout);

}  // namespace armctl::ros_test
