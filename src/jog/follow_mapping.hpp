// Leader and follower (`armctl follow`, docs/servo.md): where the follower should be for
// where the leader stands. Two arms of one family copy joint to joint (each follower joint =
// the leader's times a scale plus an offset); arms of different families (an xArm leading the
// SCARA or the reverse) copy the tool: the leader's tool motion since the start, scaled,
// added to where the follower's tool started, clipped to the follower's reach, its rotation
// as far as the follower can turn. The grippers follow as closed fractions. Pure: positions in,
// servo commands out.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "arm/arm_kinematics.hpp"
#include "arm/servo_commands.hpp"
#include "core/error.hpp"

namespace armctl::jog {

struct FollowOptions {
  // Same family: per joint (the model's order, chain joints; empty: 1 and 0). The offset is
  // SI (rad or m).
  std::vector<double> joint_scale, joint_offset;
  // Different families: the tool's motion times this, plus this offset (m, base frame).
  double tool_scale = 1;
  Eigen::Vector3d tool_offset = Eigen::Vector3d::Zero();
};

class FollowMapping {
 public:
  // Errors (invalid_argument, naming the option and what is allowed): scales or offsets of
  // the wrong count or not finite, a scale of 0 or beyond +-10, a tool scale outside
  // (0, 10]. `leader_start` and `follower_start` (SI, every joint): where both stand at the
  // start, the anchors of a tool mapping.
  static Result<FollowMapping> make(std::shared_ptr<const arm::ArmKinematics> leader,
                                    std::shared_ptr<const arm::ArmKinematics> follower, FollowOptions options,
                                    const std::vector<double>& leader_start, const std::vector<double>& follower_start);

  bool by_joints() const { return by_joints_; }
  // The follower's command for the leader at `leader` (SI, every joint).
  arm::ServoCommand command(const std::vector<double>& leader) const;
  // Where the follower's tool should be for the leader at `leader` (base frame, m): the
  // tracking error is measured against it.
  Eigen::Vector3d tool_target(const std::vector<double>& leader) const;

 private:
  std::shared_ptr<const arm::ArmKinematics> leader_, follower_;
  FollowOptions options_;
  bool by_joints_ = true;
  motion::Pose leader_start_, follower_start_;
};

}  // namespace armctl::jog
