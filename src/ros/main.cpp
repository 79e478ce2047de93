// armctl_ros: one arm (the xArm or the SCARA, on any device URI armctl knows, the embedded
// simulators included) as a ROS 1 node. Docs: docs/ros.md.
//   armctl_ros _arm:=xarm|scara|FILE _device:=URI   (empty device: the embedded simulator)
// The arm worker (session/arm_worker.hpp) owns the arm; this thread watches the ROS master
// and the link: after a master restart everything is registered again (a new ArmNode), and
// a link down for longer than ~link_timeout ends the node with a clear error (exit code 2;
// the launch files respawn it, which opens the device again).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

#include <fmt/core.h>
#include <ros/ros.h>

#include "ros/arm_bridge.hpp"
#include "ros/arm_node.hpp"

namespace {

using namespace armctl::ros_node;

double param_in(ros::NodeHandle& nh, const char* name, double fallback, double lower, double upper) {
  double v = fallback;
  nh.param(name, v, fallback);
  if (!std::isfinite(v) || v < lower || v > upper)
    throw std::invalid_argument(fmt::format("parameter ~{} = {} is not allowed: {}..{}", name, v, lower, upper));
  return v;
}

// An optional true/false parameter: empty when it is not set; anything else than a boolean
// is refused naming it.
std::optional<bool> switch_param(ros::NodeHandle& nh, const char* name) {
  if (!nh.hasParam(name)) return std::nullopt;
  bool on = false;
  if (!nh.getParam(name, on))
    throw std::invalid_argument(fmt::format("parameter ~{} is not allowed: true or false (or leave it out: as the "
                                            "scene file says)",
                                            name));
  return on;
}

int run(int argc, char** argv) {
  ros::init(argc, argv, "armctl_ros");
  ros::NodeHandle private_nh("~");
  BridgeOptions options;
  private_nh.param<std::string>("arm", options.arm, "xarm");
  private_nh.param<std::string>("device", options.device, "");
  private_nh.param<std::string>("scene", options.scene, "");
  options.fence = switch_param(private_nh, "fence");
  options.reduced_mode = switch_param(private_nh, "reduced_mode");
  options.goal_time = param_in(private_nh, "goal_time_tolerance", 1.0, 0.01, 60);
  options.move_speed = param_in(private_nh, "speed", options.move_speed, 0.01, 1);
  const double link_timeout = param_in(private_nh, "link_timeout", 5.0, 0, 3600);
  // joint_states: one per position read, ~rate a second (the link's pace if that is slower;
  // 0: back to back, as fast as the link answers, which on the embedded simulators is
  // thousands a second).
  const double rate = param_in(private_nh, "rate", 50.0, 0, 1000);
  options.poll = rate > 0 ? 1.0 / rate : 0.0;

  ArmBridge arm(options);
  ROS_INFO("armctl_ros: arm %s on %s", arm.info().name.c_str(),
           options.device.empty() ? "the embedded simulator" : options.device.c_str());
  NodeCounters counters;
  ros::AsyncSpinner spinner(4);
  spinner.start();

  // The master's parameters tell whether it is the one this node registered with: a
  // restarted master (however quickly it came back) has lost the marker.
  const std::string marker = "armctl_ros_registered";
  auto node = std::make_unique<ArmNode>(arm, counters, options.device);
  private_nh.setParam(marker, true);
  bool master_up = true;
  // Not a std::optional: g++ 12 -O2 warns it may be read uninitialised.
  bool link_down = false;
  std::chrono::steady_clock::time_point link_down_since{};
  while (ros::ok()) {
    const bool up = ros::master::check();
    if (!up && master_up) ROS_WARN("armctl_ros: the ROS master went away; waiting for it");
    if (up && !private_nh.hasParam(marker)) {
      ROS_INFO("armctl_ros: a new ROS master; registering again");
      node.reset();
      node = std::make_unique<ArmNode>(arm, counters, options.device);
      private_nh.setParam(marker, true);
    }
    master_up = up;

    const ArmState s = arm.state();
    if (s.link_ok) {
      link_down = false;
    } else if (!s.link_error.empty()) {
      const auto now = std::chrono::steady_clock::now();
      if (!link_down) {
        link_down = true;
        link_down_since = now;
        ROS_ERROR("armctl_ros: link lost: %s", s.link_error.c_str());
      }
      if (link_timeout > 0 && now - link_down_since > std::chrono::duration<double>(link_timeout)) {
        const auto why = fmt::format("armctl_ros: device lost: no position read for {:.1f} s ({}); exiting so that "
                                     "it is opened again (the launch files respawn the node)",
                                     link_timeout, s.link_error);
        ROS_FATAL("%s", why.c_str());
        std::fprintf(stderr, "%s\n", why.c_str());
        node.reset();
        return 2;
      }
    }
    // The master and the link are looked at twice a second.
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  node.reset();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "armctl_ros: %s\n", e.what());
    return 1;
  }
}
