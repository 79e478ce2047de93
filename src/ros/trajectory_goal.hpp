// A joint trajectory as ROS sends it (FollowJointTrajectory goals, the JointTrajectory
// topic): its joint names mapped to the arm's, its points put in the model's order, and
// planned by the one planner (arm::plan_moves, a TrajectoryMove: the spline of
// arm/spline_motion.hpp) for the runner. Free of ROS types, so that it is tested without a
// roscore (tests/ros/trajectory_goal_test.cpp). Docs: docs/ros.md "Trajectories". Joints
// the trajectory does not name (only the gripper may be left out) hold where they are.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "arm/arm_model.hpp"
#include "arm/motion_executor.hpp"
#include "arm/plan_moves.hpp"
#include "core/error.hpp"
#include "ros/trajectory_types.hpp"

namespace armctl::ros_node {

// Per joint (the model's order), what FollowJointTrajectory's tolerances ask; empty: the
// default. A negative tolerance in the message means "not checked" (here: infinity).
struct GoalTolerances {
  std::vector<std::optional<double>> path, goal;
  std::optional<double> goal_time;  // s after the last point
};

struct TrajectoryPlan {
  arm::Plan plan;              // for the runner (arm::run_motion): one motion piece
  arm::PlannedMotion motion;   // that piece's motion
  std::vector<double> target;  // every joint at the end (SI, the model's order)
  std::vector<int> joints;     // for each of the request's joint names, its model index
};

// How close a point at time 0 must be to where the arm stands (the motion starts there).
struct StartTolerance {
  double angle = 0.02;    // rad
  double length = 0.002;  // m
};

// The joint names: every chain joint exactly once, the gripper optional, nothing else
// (invalid_joints). Returns the model index of each name.
Result<std::vector<int>> map_joint_names(const arm::ArmModel& model, const std::vector<std::string>& names);

// Everything before anything moves: names, sizes, finite values, times after 0 and rising,
// every point and the interpolated motion within the joints' position, velocity and
// acceleration limits. `from`: where the arm stands (SI, every joint).
Result<TrajectoryPlan> plan_trajectory(const arm::ArmModel& model, const std::vector<double>& from,
                                       const TrajectoryRequest& request, const StartTolerance& start = {});
// The same with the arm's kinematics, whose collision world (its scene, docs/scene.md) the
// plan is checked against; the model's own (self-collision only) in the form above.
Result<TrajectoryPlan> plan_trajectory(const arm::ArmKinematics& kinematics, const std::vector<double>& from,
                                       const TrajectoryRequest& request, const StartTolerance& start = {});

// The tolerances of a goal in the model's order; a name that is not a joint of the
// trajectory, a NaN: refused (invalid_joints / invalid_goal).
Result<GoalTolerances> map_tolerances(const arm::ArmModel& model, const std::vector<std::string>& names,
                                      const std::vector<JointTolerance>& path, const std::vector<JointTolerance>& goal,
                                      double goal_time);

// The error of a refusal: refusals carry their code as the Error's detail.
GoalRefusal refusal_of(const Error& e);

}  // namespace armctl::ros_node
