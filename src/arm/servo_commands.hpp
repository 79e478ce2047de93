// What the servo mode follows (arm/run_servo.hpp, docs/servo.md): a stream of commands, each
// one replacing the last. Any thread may send them (a Python script, the ROS node, the web
// server); the servo loop takes the newest at every cycle. A command that is not renewed
// within the loop's timeout counts as "stop": the arm slows to rest (a dead host, a lost
// connection, a released key).
#pragma once

#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "arm/arm_kinematics.hpp"
#include "core/error.hpp"

namespace armctl::arm {

// The frame a tool twist is given in: the arm's base frame, or the tool's own (x forward
// along the tool's x axis, and so on, as the tool is turned now).
enum class ServoFrame { base, tool };
const char* to_string(ServoFrame frame);

// The tool point's velocity: linear m/s, angular rad/s (about the tool point).
struct ToolTwist {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();
  ServoFrame frame = ServoFrame::base;
};
// Per joint (SI/s, the model's order, every joint; the gripper's entry is ignored: the
// gripper is commanded by ServoCommand::gripper).
struct JointVelocities {
  std::vector<double> values;
};
// Where joints should go (SI, every joint; empty entries keep those joints still).
struct JointTargets {
  std::vector<std::optional<double>> values;
};
// Where the tool should go: the nearest IK solution becomes the joints' targets.
struct PoseTarget {
  CartesianGoal goal;
};

struct ServoCommand {
  std::variant<ToolTwist, JointVelocities, JointTargets, PoseTarget> motion = ToolTwist{};
  std::optional<double> gripper;  // 0 = open .. 1 = closed
};

// The mailbox between whoever sends commands and the servo loop. Thread-safe.
class ServoInput {
 public:
  explicit ServoInput(const ArmModel& model);
  // Replaces the command the loop follows (and renews its timeout). Errors
  // (invalid_argument, naming what and what is allowed; the last command stays): a value that
  // is not finite, a joint count that is not the arm's, a gripper outside 0..1. A joint
  // target beyond the joint's limits is not an error: the joint stops at the limit.
  Status send(ServoCommand command);
  // Bring the arm to rest and end the session (idempotent).
  void finish();
  bool finishing() const;

  // The loop's side: how many commands have been sent so far (a new number is a new command,
  // its timeout starts again), and the newest one when that is not `seen` (copied only then).
  struct Newest {
    std::optional<ServoCommand> command;
    std::uint64_t sequence = 0;
    bool finish = false;
  };
  Newest take(std::uint64_t seen) const;

 private:
  Status check(const ServoCommand& command) const;

  const ArmModel& model_;
  mutable std::mutex mutex_;
  std::optional<ServoCommand> command_;
  std::uint64_t sequence_ = 0;
  bool finish_ = false;
};

}  // namespace armctl::arm
