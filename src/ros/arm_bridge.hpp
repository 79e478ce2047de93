// The arm as the ROS side of armctl_ros sees it (C++17, standard types only: see
// ros/trajectory_types.hpp for why). Behind it (arm_bridge.cpp, C++20): the arm session,
// the arm worker that owns it (session/arm_worker.hpp) and the motion lane, through which
// every motion goes: a new one replaces the running one (the running one slows down on
// its path and the arm halts first). Thread-safe: ROS callbacks call it side by side.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "motion/move_limits.hpp"
#include "ros/trajectory_types.hpp"

namespace armctl::ros_node {

struct BridgeOptions {
  std::string arm = "xarm";
  std::string device;       // "": the embedded simulator
  std::string scene;        // a scene file every plan is checked against (docs/scene.md); "": none
  // Its fence and reduced mode switched on or off from the start (empty: as the file says).
  std::optional<bool> fence, reduced_mode;
  double goal_time = 1.0;   // s: goal_time_tolerance when a goal gives none
  double move_speed = motion::kDefaultJointSpeed;  // pose goals: fraction of the velocity limits
  // s between position reads while idle (joint_states' period); 0: back to back, as fast
  // as the link answers; nothing: the device's own poll interval.
  std::optional<double> poll;
};

struct ArmInfo {
  std::string name;                 // the arm model's
  std::vector<std::string> joints;  // the model's order: the chain, then the gripper
  std::string base_frame, tool_frame;  // the URDF links the arm file names
  std::string urdf;                 // the URDF's text
  bool action_groups = false;       // a Robot Commands board (stores action groups)
};

// The newest snapshot of the arm worker.
struct ArmState {
  std::uint64_t sequence = 0;  // 0: nothing read yet
  double read_time = 0;        // s on the device's clock: when the positions were read
  bool link_ok = false;
  std::string link_error;
  std::vector<double> positions, velocities;  // SI, the model's order
  std::optional<double> battery_volts;
  std::vector<std::string> faults;
  std::string job, last_error;
  std::optional<double> progress_t;  // nominal s of the running streamed motion
};

struct MotionOutcome {
  bool ok = false;
  bool stopped = false;  // by stop(), a cancel or a newer motion: at rest on the path
  GoalError code = GoalError::none;  // trajectories: why it failed
  std::string kind;      // on failure: the error's kind as armctl names it ("invalid argument")
  std::string message;
  // A planned move (move_to): how long it takes (s) and every joint where it ends (SI).
  double duration = 0;
  std::vector<double> targets;
};

// For feedback: where the trajectory wants every joint now (the model's order).
struct Desired {
  double t = 0;
  std::vector<double> positions, velocities;
};

class ArmBridge {
 public:
  // Opens the arm; throws std::runtime_error (armctl's ArmctlError) saying what was wrong.
  explicit ArmBridge(const BridgeOptions& options);
  ~ArmBridge();  // halts the arm
  ArmBridge(const ArmBridge&) = delete;
  ArmBridge& operator=(const ArmBridge&) = delete;

  const ArmInfo& info() const;
  ArmState state() const;
  ArmState wait_for_update(std::uint64_t after, std::chrono::milliseconds timeout) const;

  // Checks a trajectory goal against the arm where it stands now: a refusal, or nothing
  // (and its duration, s).
  std::optional<GoalRefusal> check(const TrajectoryGoal& goal, double* duration = nullptr) const;
  // Replaces the running motion with `goal` and blocks until it has ended. `on_progress`
  // (may be empty) is called from this thread at every snapshot while it runs.
  MotionOutcome follow(const TrajectoryGoal& goal,
                       const std::function<void(const Desired&, const ArmState&)>& on_progress);
  // PTP to a tool pose in the base frame (m, unit quaternion w x y z); blocks until there.
  MotionOutcome move_to(const std::vector<double>& position, const std::vector<double>& quaternion);
  MotionOutcome set_torque(bool on);
  // The joints' held faults cleared (ArmDevice::clear_faults): each holds where it is and drives again.
  MotionOutcome clear_faults();
  MotionOutcome gripper(double closed_fraction);
  MotionOutcome run_action_group(int group, int times);
  MotionOutcome stop_action_group();
  // The planning scene, one object at a time (scene::with_object / without_object): `object`
  // is one object as a scene file writes it (JSON, mm, deg). Taken at once, without waiting
  // for a motion: the running one's look-ahead sees it (docs/scene.md "While it moves").
  MotionOutcome set_scene_object(const std::string& object);
  MotionOutcome remove_scene_object(const std::string& name);
  // The scene's fence and reduced mode switched on or off (docs/scene.md "Fence and reduced
  // mode"), taken at once like a scene edit; and whether each is on (empty: none set).
  MotionOutcome set_fence(bool on);
  MotionOutcome set_reduced_mode(bool on);
  struct Limits {
    std::optional<bool> fence, reduced_mode;
  };
  Limits limits() const;
  // Stops what runs (it slows down on its path, then every joint holds); returns at once.
  void stop();

  // The servo mode (docs/servo.md), as MoveIt Servo's topics give it: the tool at `linear`
  // m/s turning at `angular` rad/s (x, y, z) in the base frame, or in the tool's when
  // `tool_frame`; or the named joints at `velocities` (rad/s, m/s), the others still. The
  // first command starts a servo session, commands not renewed within 0.2 s bring the arm to
  // rest. Returns "" when followed, else why not (a bad value, a name the arm lacks, another
  // motion running).
  std::string servo_twist(const std::vector<double>& linear, const std::vector<double>& angular, bool tool_frame);
  std::string servo_joints(const std::vector<std::string>& names, const std::vector<double>& velocities);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace armctl::ros_node
