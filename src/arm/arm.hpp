// The Arm API: one arm, in SI units with named joints, over any device. Every application
// (CLI, programs, ROS node, Python, web dashboard) is written against this type.
//
// Values: joint positions in rad (revolute) or m (prismatic), in the model's joint order
// (the chain base to tool, then the gripper); poses in metres and quaternions (RPY helpers
// in motion/kinematics.hpp). Every command is validated against the arm's limits and the
// device's range before anything is sent: a refused command sends nothing. Not
// thread-safe: one thread uses one Arm.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "arm/arm_device.hpp"
#include "arm/arm_kinematics.hpp"
#include "arm/arm_model.hpp"
#include "arm/stall_watch.hpp"
#include "core/clock.hpp"
#include "core/error.hpp"
#include "motion/kinematics.hpp"
#include "motion/move_limits.hpp"

namespace armctl::arm {

struct PtpMove;  // arm/plan_moves.hpp

struct JointState {
  TimePoint time{};              // on the device's clock, when the positions were read
  std::vector<double> positions;  // SI, every joint
  std::vector<double> device;     // the same in device units, as read
};

struct MoveOptions {
  // This long (all joints arrive together), but never faster than the arm file allows: a
  // duration shorter than the jerk-limited move at the joints' limits is stretched to it
  // (arm/motion_planning.hpp joint_move_duration, the rule of every app). Without it, the
  // slowest joint moves at `speed` times its velocity limit with its acceleration limit.
  std::optional<Duration> duration;
  double speed = motion::kDefaultJointSpeed;  // fraction of the velocity limits (motion/move_limits.hpp)
  // The duration in the user's words, for the note ("--time 0.1s"), and where the note
  // goes when the duration is stretched (called before the move is sent).
  std::string duration_words = "the duration";
  std::function<void(const std::string&)> on_note = nullptr;
};

// How close and how soon a joint must arrive at its target, in every app (Arm::wait).
inline constexpr Duration kArrivalTimeout = std::chrono::seconds(10);
inline constexpr double kArrivalAngleTolerance = 0.0087;   // rad (0.5 deg: two xArm servo units)
inline constexpr double kArrivalLengthTolerance = 0.0005;  // m

struct WaitOptions {
  Duration timeout = kArrivalTimeout;
  // Between position reads; empty: the device's own (500 ms on HID, 200 ms on serial).
  std::optional<Duration> poll;
  double angle_tolerance = kArrivalAngleTolerance;
  double length_tolerance = kArrivalLengthTolerance;
  // Per joint (SI, the model's order): where given and above 0, it replaces the one above.
  std::vector<double> joint_tolerance;
  // Asked between reads (a Ctrl-C flag, e.g. Python's KeyboardInterrupt): true ends the wait
  // at once with an error (device, "wait interrupted"); the arm is left as it is.
  std::function<bool()> interrupted;
  // After every read (a thread publishing live positions while the wait runs).
  std::function<void(const JointState&)> on_read;
  // Stall protection (arm/stall_watch.hpp): a joint of the move driven but standing still
  // this long is stopped and released (error device, detail JointStall). 0: off.
  Duration stall_time = kStallTime;
};

class Arm {
 public:
  Arm(ArmModel model, std::unique_ptr<ArmDevice> device);

  // The model the arm drives with now. The reference stays valid as long as the Arm, also
  // after use_model (a caller that keeps it goes on reading the model it was given).
  const ArmModel& model() const { return current()->model(); }
  // Drives with `model` from now on (a calibration was confirmed: new zeros, directions,
  // limits, gripper or link lengths), the scene, fence and reduced mode kept as they are.
  // It must name the same joints with the same device IDs (what the device talks to does
  // not change); nothing changes when it does not (invalid_argument, naming what differs).
  // Call it while the arm does not move: plans made before keep the model they were made with.
  Status use_model(ArmModel model);
  // The arm's kinematics (model, FK/IK, target checks with this device's range, the
  // collision world with the scene): an immutable value other threads and the planner may
  // hold and use while the arm moves. A new scene makes a new value (set_scene).
  std::shared_ptr<const ArmKinematics> kinematics() const {
    std::lock_guard lock(kinematics_mutex_);
    return kinematics_;
  }
  // Every plan made from kinematics() from now on is checked against `scene` (docs/scene.md);
  // plans made before keep the scene they were checked with. Errors (invalid_config): the
  // arm has no collision shapes.
  Status set_scene(scene::Scene scene);
  // Changes the scene by `edit` (scene::with_object, without_object) from the one the arm has,
  // so that two threads editing at once (an HTTP client, a ROS service) both land; an edit
  // that fails changes nothing.
  Status edit_scene(const std::function<Result<scene::Scene>(const scene::Scene&)>& edit);
  // The scene plans are checked against (empty: self-collision only, or no collision model).
  scene::Scene scene() const;
  // The scene's fence and reduced mode switched on or off (docs/scene.md "Fence and reduced
  // mode"): plans made from now on are checked with them, and a motion under way is checked
  // ahead with them (the look-ahead). Errors (invalid_argument): the scene sets none.
  Status set_fence(bool on);
  Status set_reduced_mode(bool on);
  ArmDevice& device() { return *device_; }
  const Clock& clock() const { return device_->clock(); }

  Result<JointState> read();
  // The tool pose where the arm stands now.
  Result<motion::Pose> pose();
  // The kinematics' (ArmKinematics), for callers that hold an Arm.
  motion::Pose forward(const motion::JointVector& chain) const { return current()->forward(chain); }
  Result<std::vector<motion::IkSolution>> inverse(const CartesianGoal& goal, const JointState& now) const {
    return current()->inverse(goal, now.positions);
  }
  motion::Rpy tool_rpy(const motion::Pose& pose, const motion::JointVector& chain) const {
    return current()->tool_rpy(pose, chain);
  }
  motion::Rpy goal_rpy(const CartesianGoal& goal, const motion::Rpy& current_rpy) const {
    return current()->goal_rpy(goal, current_rpy);
  }
  motion::JointVector chain_of(const std::vector<double>& positions) const { return current()->chain_of(positions); }

  // Moves the joints that have a target (SI; the vector has one entry per joint): a board
  // move (the device interpolates) planned by arm::plan_moves, then sent (send()).
  Status move_joints(const std::vector<std::optional<double>>& targets, const MoveOptions& options = {});
  // Moves the tool (PTP: joint-space move to the IK solution nearest the current joints).
  Status move_to(const CartesianGoal& goal, const MoveOptions& options = {});
  // Sends targets already checked and timed (a board move of a plan, arm/plan_moves.hpp):
  // the device interpolates to them over `duration`; wait() then waits for them.
  Status send(const std::vector<std::optional<double>>& targets, Duration duration);
  // Gripper: 0 = open, 1 = closed.
  Status gripper(double closed_fraction, const MoveOptions& options = {});
  // Closed loop: reads positions until every joint of the last move is within tolerance of
  // its target and has come to rest there (two reads in a row within a quarter of the
  // tolerance of each other); the error (timeout) names every joint that did not arrive,
  // with where it is. A joint that stalls (standing still away from its target for the
  // options' stall_time after the move's time is up) is stopped and released (stalled()).
  Result<JointState> wait(const WaitOptions& options = {});
  Status stop();
  Status set_torque(bool on);
  // The motion executor's last point (SI, every joint): wait() then waits for the arm to
  // arrive there, as after move_joints.
  void expect_at(const std::vector<double>& positions);
  // Stall protection (arm/stall_watch.hpp): a watch with this arm's thresholds (every joint
  // but the gripper, which stops on a part by design), and what is done when it fires: the
  // arm stopped where it stands, the stalled joint's torque released, and the error (device,
  // detail JointStall) naming the joint, where it stood and for how long.
  StallWatch stall_watch(Duration time) const;
  Error stalled(JointStall stall, const std::string& what = "");

  // Checks targets against the joint limits and the device's range (ArmKinematics); the
  // error names the joint, the value and what is allowed.
  Status check_targets(const std::vector<std::optional<double>>& targets) const {
    return current()->check_targets(targets);
  }

 private:
  const ArmKinematics* current() const { return current_.load(std::memory_order_acquire); }
  Status move_board(PtpMove move, const MoveOptions& options);

  // The model's kinematics without the scene: the newest is current_. Those replaced by
  // use_model stay alive with the Arm, so that references model() gave out stay valid.
  std::vector<std::shared_ptr<const ArmKinematics>> models_;
  std::atomic<const ArmKinematics*> current_{nullptr};
  mutable std::mutex kinematics_mutex_;
  std::shared_ptr<const ArmKinematics> kinematics_;  // with the scene; replaced by set_scene
  std::mutex scene_edit_mutex_;  // one edit_scene at a time
  std::unique_ptr<ArmDevice> device_;
  std::vector<std::optional<double>> last_targets_;  // SI, of the last move
  // When the last move was sent and how long the device takes for it: from then on each of
  // its joints is driven to its target (stall protection).
  TimePoint move_sent_{};
  Duration move_duration_{};
};

}  // namespace armctl::arm
