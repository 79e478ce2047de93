// The plain types the ROS side (arm_node.cpp, main.cpp) and the arm side (arm_bridge.cpp,
// trajectory_goal.cpp) share. ROS 1's generated message headers do not compile as C++20
// (they use std::allocator<void>::rebind, removed in C++20), so the ROS side is built as
// C++17 and sees armctl only through this header and ros/arm_bridge.hpp: standard types
// only, no armctl header.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace armctl::ros_node {

struct TrajectoryPoint {
  double time = 0;  // s from the start
  std::vector<double> positions, velocities, accelerations, effort;  // in joint_names' order
};

struct TrajectoryRequest {
  std::vector<std::string> joint_names;
  std::vector<TrajectoryPoint> points;
};

// The longest trajectory a goal may give (s), and the furthest ahead its header stamp may
// start it: more is taken for a mistake (a stamp in another clock, a unit slip).
constexpr double kLongestTrajectory = 3600;

// control_msgs/FollowJointTrajectoryResult's error codes.
enum class GoalError { none = 0, invalid_goal = -1, invalid_joints = -2, old_header_timestamp = -3,
                       path_tolerance_violated = -4, goal_tolerance_violated = -5 };

struct GoalRefusal {
  GoalError code = GoalError::invalid_goal;
  std::string message;
};

// control_msgs/JointTolerance's position (velocity and acceleration are not checked).
struct JointTolerance {
  std::string name;
  double position = 0;  // 0: the default; negative: not checked
};

// A FollowJointTrajectory goal (or a streamed trajectory: no tolerances).
struct TrajectoryGoal {
  TrajectoryRequest request;
  std::vector<JointTolerance> path_tolerance, goal_tolerance;
  double goal_time_tolerance = 0;  // s; 0: the node's default
};

}  // namespace armctl::ros_node
