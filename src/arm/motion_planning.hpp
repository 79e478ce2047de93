// Planning host-computed motions for the executor (arm/motion_executor.hpp), from where the
// arm stands: a jerk-limited joint-space move (PTP, optionally through waypoints) and a
// Cartesian path (LIN/CIRC with blended corners) timed along its length. Everything is
// checked before the first byte goes out: the joint limits, and for paths the whole path
// (motion/path_check.hpp). Pure planning: no I/O. Docs: docs/motion.md.
#pragma once

#include <cmath>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "arm/arm_kinematics.hpp"
#include "arm/arm_model.hpp"
#include "arm/motion_executor.hpp"
#include "core/error.hpp"
#include "motion/cartesian_path.hpp"
#include "motion/move_limits.hpp"
#include "motion/path_check.hpp"
#include "files/path_file.hpp"
#include "motion/trajectory.hpp"

namespace armctl::arm {

// A joint-space move: through `waypoints` (if any) to `target`, every joint (SI, one per
// joint of the arm) at `speed` of its velocity limit, the acceleration and jerk limits of
// the arm file; every joint starts and ends together, passing the waypoints without stopping.
struct JointMove {
  std::vector<std::vector<double>> waypoints;
  std::vector<double> target;
  double speed = motion::kDefaultJointSpeed;  // (0, 1]
  double min_duration = 0;  // s
};
Result<PlannedMotion> plan_joint_move(const ArmModel& model, const std::vector<double>& from, const JointMove& move);

// The one rule for a duration people ask of a joint move, in every app (the CLI's --time,
// Python's duration=, the HTTP API's duration, a board move or a host-planned one): never
// faster than the arm file allows. The shortest a move may take is that of the jerk-limited
// move with every joint at its velocity, acceleration and jerk limits (plan_joint_move at
// speed 1); a duration asked below it is stretched to it, and the note says so. Refused:
// a duration that is not a number, negative or above motion::kMaxMoveDuration.
struct MoveDuration {
  double seconds = 0;   // what the move takes
  double shortest = 0;  // the shortest the arm file's limits allow
  bool stretched = false;
  // When stretched, for people: "--time 0.1s is too short for servo6 to move 194.8 deg
  // within its limits (180.0 deg/s): the move takes 1.46 s".
  std::string note;
};
// `from` and `to`: SI, every joint. `as_given`: the duration in the user's words ("--time
// 0.1s", "duration=0.1").
Result<MoveDuration> joint_move_duration(const ArmModel& model, const std::vector<double>& from,
                                         const std::vector<double>& to, double requested_s, std::string_view as_given);

// A PTP's joint values as a path file or a program gives them: the leading joints, each an
// angle or a length as its joint is; the joints not given stay where `from` has them. The
// target (SI, every joint), or why not (too many values, a value of the wrong kind).
Result<std::vector<double>> joint_values_target(const ArmModel& model, const std::vector<double>& from,
                                                const std::vector<files::JointValue>& values);
// The same as targets (one per joint; the joints not given are empty: a PtpMove keeps them).
Result<std::vector<std::optional<double>>> joint_values_targets(const ArmModel& model,
                                                                const std::vector<files::JointValue>& values);

// The timing of a Cartesian path along its length: how fast the tool may speed up and slow
// down (the speed of each segment is in the segment).
struct PathTiming {
  double acceleration = motion::kDefaultToolAcceleration;                 // m/s^2 of the tool point
  double angular_acceleration = motion::kDefaultToolAngularAcceleration;  // rad/s^2 of the tool
};

// What a Cartesian plan knows besides the motion: the path and its check (where it was
// slowed and why), for progress lines and reports.
struct PathPlan {
  PlannedMotion motion;
  std::shared_ptr<const motion::CartesianPath> path;
  std::shared_ptr<const motion::CheckedPath> checked;
};
Result<PathPlan> plan_path(const ArmKinematics& kinematics, const std::vector<double>& from,
                           std::span<const motion::PathSegment> segments, const PathTiming& timing = {});
// The same without a device (the joint limits only).
Result<PathPlan> plan_path(const ArmModel& model, const std::vector<double>& from,
                           std::span<const motion::PathSegment> segments, const PathTiming& timing = {});

// A LIN or CIRC target as people give it: orientation components left empty keep the ones
// the tool has at the end of the move before (ArmKinematics::goal_rpy; on the xArm an empty
// yaw follows the position). Speeds that are not given: motion/move_limits.hpp's defaults.
struct CartesianMove {
  motion::SegmentKind kind = motion::SegmentKind::lin;
  CartesianGoal goal;
  Eigen::Vector3d via = Eigen::Vector3d::Zero();  // circ: a point on the arc (m)
  double speed = motion::kDefaultToolSpeed;
  double angular_speed = motion::kDefaultToolAngularSpeed;
  double zone = 0;  // m
  // m/s^2 of the tool point (a program's ACCEL): the run's smallest times the whole path.
  std::optional<double> acceleration;
};
// The path segments of `moves` made one after the other from the joints `from` (SI, every
// joint): each target's orientation filled in from the one before, the first from the tool's.
std::vector<motion::PathSegment> path_segments(const ArmKinematics& kinematics, const std::vector<double>& from,
                                               std::span<const CartesianMove> moves);

// How far the tool point can be from where it is asked to be only because each chain joint
// stands on a whole device unit: the tool displacement of half a unit on every chain joint
// (through the Jacobian at `q`, SI, every joint). The quantization limit of a path's accuracy.
double tool_quantization(const ArmModel& model, Protocol protocol, const std::vector<double>& q);

// The chain joints' limits as the path check takes them.
std::vector<motion::PathLimits> path_limits(const ArmModel& model);

}  // namespace armctl::arm
