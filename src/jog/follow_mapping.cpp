#include "jog/follow_mapping.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace armctl::jog {
namespace {

Error bad(std::string message) { return Error{ErrorKind::invalid_argument, std::move(message)}; }

constexpr double kMostScale = 10;

}  // namespace

Result<FollowMapping> FollowMapping::make(std::shared_ptr<const arm::ArmKinematics> leader,
                                          std::shared_ptr<const arm::ArmKinematics> follower, FollowOptions options,
                                          const std::vector<double>& leader_start,
                                          const std::vector<double>& follower_start) {
  FollowMapping m;
  const arm::ArmModel& l = leader->model();
  const arm::ArmModel& f = follower->model();
  m.by_joints_ = l.family == f.family && l.chain_joints() == f.chain_joints();
  const std::size_t chain = std::size_t(f.chain_joints());
  if (!m.by_joints_ && (!options.joint_scale.empty() || !options.joint_offset.empty()))
    return bad(fmt::format("joint scales and offsets copy joint to joint, between arms of one family: '{}' ({}) and "
                           "'{}' ({}) copy the tool (use the tool scale and offset)",
                           l.name, l.family, f.name, f.family));
  if (options.joint_scale.empty()) options.joint_scale.assign(chain, 1.0);
  if (options.joint_offset.empty()) options.joint_offset.assign(chain, 0.0);
  if (m.by_joints_ && (options.joint_scale.size() != chain || options.joint_offset.size() != chain))
    return bad(fmt::format("joint scales and offsets: {} and {} values, one per joint of '{}' ({}) is needed",
                           options.joint_scale.size(), options.joint_offset.size(), f.name, chain));
  for (std::size_t i = 0; i < options.joint_scale.size(); ++i) {
    const double s = options.joint_scale[i];
    if (!std::isfinite(s) || s == 0 || std::abs(s) > kMostScale)
      return bad(fmt::format("joint scale {} for joint {}: a number from -{} to {}, not 0", s, f.joints[i].name,
                             kMostScale, kMostScale));
    if (!std::isfinite(options.joint_offset[i]))
      return bad(fmt::format("joint offset for joint {}: a finite number", f.joints[i].name));
  }
  if (!(options.tool_scale > 0 && options.tool_scale <= kMostScale))
    return bad(fmt::format("tool scale {}: above 0 up to {}", options.tool_scale, kMostScale));
  if (!options.tool_offset.allFinite()) return bad("tool offset: finite x, y, z");
  if (leader_start.size() != std::size_t(l.joint_count()) || follower_start.size() != std::size_t(f.joint_count()))
    return bad("the arms' start positions need one value per joint");
  m.leader_ = std::move(leader);
  m.follower_ = std::move(follower);
  m.options_ = std::move(options);
  m.leader_start_ = m.leader_->pose_at(leader_start);
  m.follower_start_ = m.follower_->pose_at(follower_start);
  return m;
}

Eigen::Vector3d FollowMapping::tool_target(const std::vector<double>& leader) const {
  const Eigen::Vector3d moved = leader_->pose_at(leader).position - leader_start_.position;
  Eigen::Vector3d p = follower_start_.position + options_.tool_scale * moved + options_.tool_offset;
  // Clipped to the follower's reach: a leader that reaches farther holds the follower at the
  // edge instead of sending it a target it cannot have.
  const double reach = follower_->model().reach;
  if (p.norm() > reach) p *= reach / p.norm();
  return p;
}

arm::ServoCommand FollowMapping::command(const std::vector<double>& leader) const {
  const arm::ArmModel& l = leader_->model();
  const arm::ArmModel& f = follower_->model();
  arm::ServoCommand c;
  if (l.gripper && f.gripper)
    c.gripper = std::clamp(l.gripper->fraction(leader[std::size_t(l.gripper->joint)]), 0.0, 1.0);
  if (by_joints_) {
    std::vector<std::optional<double>> targets(std::size_t(f.joint_count()));
    for (std::size_t i = 0; i < std::size_t(f.chain_joints()); ++i)
      targets[i] = leader[i] * options_.joint_scale[i] + options_.joint_offset[i];
    c.motion = arm::JointTargets{std::move(targets)};
    return c;
  }
  // The leader tool's rotation since the start, applied to the follower tool's start.
  const motion::Pose now = leader_->pose_at(leader);
  const Eigen::Quaterniond turned = now.orientation * leader_start_.orientation.inverse();
  const motion::Rpy rpy = motion::to_rpy(turned * follower_start_.orientation);
  arm::CartesianGoal goal;
  goal.position = tool_target(leader);
  goal.roll = rpy.roll;
  goal.pitch = rpy.pitch;
  goal.yaw = rpy.yaw;
  // As far as the follower can turn: the 5-joint xArm takes the nearest orientation.
  goal.nearest_orientation = follower_->reaches_nearest_orientation();
  c.motion = arm::PoseTarget{goal};
  return c;
}

}  // namespace armctl::jog
