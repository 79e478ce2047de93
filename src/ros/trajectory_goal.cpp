#include "ros/trajectory_goal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include <fmt/core.h>
#include <fmt/ranges.h>

#include "arm/plan_moves.hpp"
#include "core/quantity.hpp"

namespace armctl::ros_node {

namespace {

Error refused(GoalError code, std::string message) {
  return Error{ErrorKind::invalid_argument, std::move(message), code};
}

std::vector<std::string> names_of(const arm::ArmModel& model) {
  std::vector<std::string> out;
  for (const auto& j : model.joints) out.push_back(j.name);
  return out;
}

}  // namespace

GoalRefusal refusal_of(const Error& e) {
  if (const auto* code = e.detail_as<GoalError>()) return {*code, e.message};
  return {GoalError::invalid_goal, e.message};
}

Result<std::vector<int>> map_joint_names(const arm::ArmModel& model, const std::vector<std::string>& names) {
  const auto allowed = fmt::format("{}", fmt::join(names_of(model), ", "));
  if (names.empty())
    return refused(GoalError::invalid_joints, fmt::format("the trajectory names no joints: arm {} has {} (the gripper "
                                                          "may be left out)", model.name, allowed));
  std::vector<int> out;
  std::vector<bool> seen(std::size_t(model.joint_count()), false);
  for (const auto& n : names) {
    // Exact names: ROS tools match them as strings (tf, robot_state_publisher).
    int index = -1;
    for (int j = 0; j < model.joint_count(); ++j)
      if (model.joints[std::size_t(j)].name == n) index = j;
    if (index < 0)
      return refused(GoalError::invalid_joints,
                     fmt::format("unknown joint '{}': arm {} has joints {}", n, model.name, allowed));
    if (seen[std::size_t(index)])
      return refused(GoalError::invalid_joints, fmt::format("joint '{}' is named twice in the trajectory", n));
    seen[std::size_t(index)] = true;
    out.push_back(index);
  }
  std::vector<std::string> missing;
  for (int j = 0; j < model.chain_joints(); ++j)
    if (!seen[std::size_t(j)]) missing.push_back(model.joints[std::size_t(j)].name);
  if (!missing.empty())
    return refused(GoalError::invalid_joints,
                   fmt::format("the trajectory leaves out joint(s) {}: every joint of arm {} must be in it ({}; the "
                               "gripper may be left out)", fmt::join(missing, ", "), model.name, allowed));
  return out;
}

Result<arm::SplineRequest> spline_request(const arm::ArmModel& model, const std::vector<int>& joints,
                                          const TrajectoryRequest& request, const StartTolerance& start) {
  const std::size_t n = request.joint_names.size();
  const std::size_t all = std::size_t(model.joint_count());
  arm::SplineRequest out;
  out.start_angle_tolerance = start.angle;
  out.start_length_tolerance = start.length;
  out.longest = kLongestTrajectory;
  bool velocities = true, accelerations = true;
  for (const auto& p : request.points) {
    velocities = velocities && !p.velocities.empty();
    accelerations = accelerations && !p.accelerations.empty();
  }
  for (std::size_t k = 0; k < request.points.size(); ++k) {
    const auto& p = request.points[k];
    if (p.positions.size() != n)
      return refused(GoalError::invalid_goal, fmt::format("point {} has {} positions for {} joint names", k,
                                                          p.positions.size(), n));
    if (!p.velocities.empty() && p.velocities.size() != n)
      return refused(GoalError::invalid_goal, fmt::format("point {} has {} velocities for {} joint names (give none "
                                                          "or one per joint)", k, p.velocities.size(), n));
    if (!p.accelerations.empty() && p.accelerations.size() != n)
      return refused(GoalError::invalid_goal, fmt::format("point {} has {} accelerations for {} joint names (give "
                                                          "none or one per joint)", k, p.accelerations.size(), n));
    if (!p.effort.empty())
      return refused(GoalError::invalid_goal,
                     fmt::format("point {} gives efforts: armctl follows positions (and velocities, accelerations) "
                                 "only; leave effort empty", k));
    // In the model's order: the joints the trajectory leaves out (the gripper) hold.
    arm::SplinePoint q;
    q.time = p.time;
    q.positions.assign(all, std::nullopt);
    if (!p.velocities.empty()) q.velocities.assign(all, 0.0);
    if (!p.accelerations.empty()) q.accelerations.assign(all, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const auto j = std::size_t(joints[i]);
      q.positions[j] = p.positions[i];
      if (!p.velocities.empty()) q.velocities[j] = p.velocities[i];
      if (!p.accelerations.empty()) q.accelerations[j] = p.accelerations[i];
    }
    out.points.push_back(std::move(q));
  }
  return out;
}

Result<TrajectoryPlan> plan_trajectory(const arm::ArmModel& model, const std::vector<double>& from,
                                       const TrajectoryRequest& request, const StartTolerance& start) {
  return plan_trajectory(arm::ArmKinematics(model), from, request, start);
}

Result<TrajectoryPlan> plan_trajectory(const arm::ArmKinematics& kinematics, const std::vector<double>& from,
                                       const TrajectoryRequest& request, const StartTolerance& start) {
  const arm::ArmModel& model = kinematics.model();
  auto joints = map_joint_names(model, request.joint_names);
  if (!joints) return joints.error();
  if (from.size() != std::size_t(model.joint_count()))
    return refused(GoalError::invalid_goal, fmt::format("the arm's positions are not known ({} values)", from.size()));
  auto spline = spline_request(model, *joints, request, start);
  if (!spline) return spline.error();
  // The one planner (arm::plan_moves): a refusal there has no goal code, so it is invalid_goal.
  const arm::Move move{arm::TrajectoryMove{std::move(spline).value()}};
  auto plan = arm::plan_moves(kinematics, from, std::span<const arm::Move>(&move, 1));
  if (!plan) return plan.error();
  TrajectoryPlan out;
  out.joints = *joints;
  out.motion = plan->pieces.front().motion;
  out.target = plan->end();
  out.plan = std::move(plan).value();
  return out;
}

Result<GoalTolerances> map_tolerances(const arm::ArmModel& model, const std::vector<std::string>& names,
                                      const std::vector<JointTolerance>& path, const std::vector<JointTolerance>& goal,
                                      double goal_time) {
  // The names first (a tolerance may name any of them): every one a joint of the arm.
  if (auto known = map_joint_names(model, names); !known) return known.error();
  GoalTolerances out;
  out.path.assign(std::size_t(model.joint_count()), std::nullopt);
  out.goal = out.path;
  auto fill = [&](const std::vector<JointTolerance>& given, std::vector<std::optional<double>>& into,
                  const char* which) -> Status {
    for (const auto& t : given) {
      if (std::find(names.begin(), names.end(), t.name) == names.end())
        return refused(GoalError::invalid_joints,
                       fmt::format("{} tolerance for joint '{}', which is not a joint of the trajectory ({})", which,
                                   t.name, fmt::join(names, ", ")));
      if (std::isnan(t.position))
        return refused(GoalError::invalid_goal, fmt::format("{} tolerance of joint {} is NaN", which, t.name));
      // Exact names, as map_joint_names matched them (find_joint ignores case).
      const auto j = std::size_t(std::find_if(model.joints.begin(), model.joints.end(),
                                              [&](const arm::JointModel& m) { return m.name == t.name; }) -
                                 model.joints.begin());
      if (t.position > 0) into[j] = t.position;
      if (t.position < 0) into[j] = std::numeric_limits<double>::infinity();  // not checked
    }
    return Ok{};
  };
  if (auto s = fill(path, out.path, "path"); !s) return s.error();
  if (auto s = fill(goal, out.goal, "goal"); !s) return s.error();
  if (!std::isfinite(goal_time) || goal_time < 0)
    return refused(GoalError::invalid_goal,
                   fmt::format("goal_time_tolerance {} s is not allowed: 0 (the default) or more", goal_time));
  if (goal_time > 0) out.goal_time = goal_time;
  return out;
}

}  // namespace armctl::ros_node
