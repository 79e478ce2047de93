// The benchmark's reference figures straight from armctl, without ROS (C++20 behind a
// header with standard types: the ROS side is C++17, src/ros/trajectory_types.hpp).
#pragma once

#include <string>
#include <vector>

#include "ros/trajectory_types.hpp"

namespace armctl::ros_bench {

// The trajectory `request` planned as the node plans it (ros/trajectory_goal.hpp) and
// streamed by the motion executor on a fresh embedded simulator of `arm`, in step with the
// wall clock: the largest following error over the read-backs, the revolute chain joints
// (rad), each read compared with the plan at its instant.
double direct_following_error(const std::string& arm, const ros_node::TrajectoryRequest& request);

// Where the arm's embedded simulator stands when it starts (every joint, SI).
std::vector<double> start_positions(const std::string& arm);

}  // namespace armctl::ros_bench
