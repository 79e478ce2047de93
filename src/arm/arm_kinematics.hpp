// The arm's kinematics as one immutable value: its model (joints, limits, tool frame,
// device maps), forward and inverse kinematics with the tool frame, the tool's roll-pitch-yaw
// as people read them on this arm, and the checks of joint targets against the joint
// limits and the range of the device that drives the arm. Each arm family's rules (the
// 5-joint xArm's yaw following the position, its free tool pitch) live here, not in callers.
//
// Pure: no device, no I/O, no state. Built once from an ArmModel; shared across threads
// (std::shared_ptr<const ArmKinematics>) by the Arm, the planner (arm/plan_moves.hpp), and
// the apps' request threads, so that planning a program or a path needs no device.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "arm/arm_model.hpp"
#include "arm/reduced_mode.hpp"
#include "core/clock.hpp"
#include "core/error.hpp"
#include "motion/kinematics.hpp"
#include "scene/collision_world.hpp"

namespace armctl::arm {

// A tool target. Orientation components left empty keep the tool's current ones (the
// xArm's yaw is set by where the tool is: left empty it follows the position).
struct CartesianGoal {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::optional<double> roll, pitch, yaw;
  std::optional<motion::Elbow> elbow;  // only solutions in this configuration
  bool nearest_orientation = false;     // 5-joint arm: the nearest reachable orientation
};

class ArmKinematics {
 public:
  // `device`: the protocol of the device that drives the arm, whose range targets are checked
  // against (check_targets); empty: planning without a device (the joint limits only).
  explicit ArmKinematics(ArmModel model, std::optional<Protocol> device = std::nullopt);

  const ArmModel& model() const { return model_; }

  // What the planner checks every motion against (docs/scene.md): the arm's links (self-
  // collision) and the scene's objects. Null when no link of the URDF has a <collision> shape.
  const std::shared_ptr<const scene::CollisionWorld>& collisions() const { return collisions_; }
  // The same kinematics checking against `scene` (an empty scene: self-collision only), with
  // the arm file's fence and reduced mode where the scene sets none (with_arm_limits).
  // Errors (invalid_config) when the arm has no collision shapes to check a scene against.
  Result<std::shared_ptr<const ArmKinematics>> with_scene(scene::Scene scene) const;
  // Reduced mode while it is on (docs/scene.md "Fence and reduced mode"): its joint ranges
  // are checked by the collision world, its tool speed cap by the planner.
  const std::optional<ReducedLimits>& reduced() const { return reduced_; }
  std::optional<Protocol> device() const { return device_; }
  int joint_count() const { return model_.joint_count(); }

  // The chain joints of every joint's positions (SI, the model's order).
  motion::JointVector chain_of(const std::vector<double>& positions) const;
  // The tool pose (the arm file's tool frame applied) at chain joints / at every joint.
  motion::Pose forward(const motion::JointVector& chain) const;
  motion::Pose pose_at(const std::vector<double>& positions) const { return forward(chain_of(positions)); }

  // Every IK solution of `goal` inside the joint limits, nearest to `near` (every joint)
  // first. Orientation components left empty keep those the tool has at `near`
  // (goal_rpy); a position alone asked of the xArm frees its tool pitch (the middle of the
  // widest run of pitches that reach). Refused (invalid_argument) with why.
  Result<std::vector<motion::IkSolution>> inverse(const CartesianGoal& goal, const std::vector<double>& near) const;
  // The nearest solution as every joint: the chain from IK, the other joints as in `near`.
  Result<std::vector<double>> nearest_joints(const CartesianGoal& goal, const std::vector<double>& near) const;

  // Roll, pitch and yaw of a tool pose as people read them on this arm: on the 5-joint
  // xArm the form whose yaw is where the arm points (roll = the wrist's roll).
  motion::Rpy tool_rpy(const motion::Pose& pose, const motion::JointVector& chain) const;
  motion::Rpy tool_rpy_at(const std::vector<double>& positions) const;
  // The orientation `goal` asks for when the tool's is `current` (as tool_rpy gives it):
  // components left empty keep the current ones; where the yaw follows the position, an
  // empty yaw follows it.
  motion::Rpy goal_rpy(const CartesianGoal& goal, const motion::Rpy& current) const;
  // The goal that keeps the tool's orientation at `positions` (every joint) while it moves
  // to `position`: roll and pitch kept, the yaw kept unless it follows the position.
  CartesianGoal keeping_orientation(const Eigen::Vector3d& position, const motion::Rpy& current) const;

  // The family's rules (arm/arm_families.hpp), for the planner: the yaw is where the arm
  // points (an empty yaw follows the position); a target without a pitch leaves the tool
  // pitch free; the chain reaches positions with the nearest orientation (5 joints).
  bool yaw_follows_position() const { return model_.rules.yaw_follows_position; }
  bool pitch_free() const { return model_.rules.pitch_free; }
  bool reaches_nearest_orientation() const { return model_.rules.reaches_nearest_orientation; }

  // Targets (SI, one entry per joint; empty keeps a joint) against the joint limits and,
  // when the kinematics knows its device, the device's range (a coupled joint's device value
  // depends on its partner: taken from `from`, every joint, where the target leaves it).
  // The error (invalid_argument) names the joint, the value and what is allowed.
  Status check_targets(const std::vector<std::optional<double>>& targets,
                       const std::vector<double>* from = nullptr) const;
  Status check_targets(const std::vector<double>& targets) const;
  // The device values of `full` (every joint, SI) for the joints `sent`, each checked
  // against the device's range (the device must be known).
  Result<std::vector<std::optional<double>>> device_targets(const std::vector<double>& full,
                                                            const std::vector<bool>& sent) const;

 private:
  // Builds the collision world of `scene` (with the arm's limits) and reduced mode's limits.
  Status install(scene::Scene scene);
  ArmModel model_;
  std::optional<Protocol> device_;
  std::shared_ptr<const scene::CollisionWorld> collisions_;
  std::optional<ReducedLimits> reduced_;
};

// `scene` with the arm file's fence and reduced mode (ArmModel::fence, reduced) where it sets
// none of its own: a scene's fence replaces the arm file's, its reduced mode likewise.
scene::Scene with_arm_limits(scene::Scene scene, const ArmModel& model);

// "30.000 deg" / "120.000 mm" for joint `index` of `model`.
std::string format_joint_value(const ArmModel& model, int index, double si);

// The arm against `scene` alone, its own links never against each other (what a simulated
// arm meets: arm/scene_obstacle.hpp). Errors: as with_scene's.
Result<std::shared_ptr<const scene::CollisionWorld>> scene_only_world(const ArmModel& model, scene::Scene scene);

}  // namespace armctl::arm
