// What the ROS node tests compare the node with, straight from armctl (the arm model and
// its kinematics), behind a header with standard types only (the tests are C++17 because
// of ROS: src/ros/trajectory_types.hpp).
#pragma once

#include <string>
#include <vector>

namespace armctl::ros_test {

struct ReferenceJoint {
  std::string name;
  double lower = 0, upper = 0, velocity = 0;
  bool chain = true;     // false: the gripper
  bool revolute = true;  // false: prismatic (m)
};

std::vector<ReferenceJoint> reference_joints(const std::string& arm);

// armctl's forward kinematics with the arm file's tool frame (Arm::forward): x, y, z (m),
// w, x, y, z of the tool in the base frame, at every joint's `positions`.
std::vector<double> reference_tool_pose(const std::string& arm, const std::vector<double>& positions);
// How long one position read of every joint takes on the arm's embedded simulator (in step
// with the wall clock, as the node runs it), the mean of `reads`: the link's refresh floor.
double reference_read_seconds(const std::string& arm, int reads);

// The tool frame in the URDF's tool link: x, y, z, w, x, y, z.
std::vector<double> reference_tool_offset(const std::string& arm);

}  // namespace armctl::ros_test
