// Everything armctl_ros offers on one ROS master: the topics it publishes, the trajectory
// action, the command topics and the services. Built anew when the master comes back after
// a restart (main.cpp), so that it registers everything again; the arm (ArmBridge) outlives
// it. C++17 (ros/trajectory_types.hpp says why). Docs: docs/ros.md.
#pragma once

#include <memory>
#include <mutex>
#include <string>

#include "ros/arm_bridge.hpp"

namespace armctl::ros_node {

// What the node counts across masters (diagnostics).
struct NodeCounters {
  std::mutex mutex;
  int refused = 0, succeeded = 0, failed = 0, canceled = 0;
  std::string last_refusal, last_failure;
  void refusal(const std::string& why);
  void failure(const std::string& why);
};

class ArmNode {
 public:
  ArmNode(ArmBridge& arm, NodeCounters& counters, const std::string& device);
  ~ArmNode();  // stops a running goal's motion, joins its threads
  ArmNode(const ArmNode&) = delete;
  ArmNode& operator=(const ArmNode&) = delete;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace armctl::ros_node
