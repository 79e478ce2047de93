// The servo mode (docs/servo.md): the arm follows a stream of commands (arm/servo_commands.hpp)
// cycle by cycle, as MoveIt Servo does: a tool twist, joint velocities, joint or pose targets,
// the gripper. Every cycle the newest command is turned into a goal per joint and the servo
// generator (motion/servo_generator.hpp) takes one jerk-limited step toward it from the state
// it reached in the cycle before, and that point is streamed to the device.
//
// It slows down instead of stopping dead or jumping:
// - near the end of a joint's range (the whole twist is scaled so that the tool keeps its
//   direction; the joint stops at the end),
// - near a singularity of the tool point's position (when the command moves toward it),
// - near scene objects and the arm's own links (when the command moves toward them), and it
//   brakes when the place it would come to rest if it braked one cycle later touches anything:
//   it never reaches contact,
// and it comes to rest when commands stop coming (command_timeout) or the input finishes.
// Every mode reads the arm back as the executor does and halts on a following error.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "arm/arm.hpp"
#include "arm/motion_executor.hpp"
#include "arm/servo_commands.hpp"
#include "core/clock.hpp"
#include "core/error.hpp"

namespace armctl::arm {

// Why a cycle went slower than the command asked.
enum class ServoSlowdown { none, joint_limit, singularity, collision, unreachable, command_timeout };
inline constexpr int kServoSlowdowns = 6;
const char* to_string(ServoSlowdown why);

struct ServoStatus {
  Duration elapsed{};  // since the session began, when the arm is due at the point sent
  std::vector<double> positions, velocities;  // the point just sent (SI, every joint)
  double scale = 1;  // of the command's speed this cycle (1: as asked)
  ServoSlowdown slowdown = ServoSlowdown::none;
  std::string detail;  // the joint, the two bodies, why a pose cannot be reached
  bool commanded = false;  // a command is being followed (not timed out, not finishing)
  bool at_rest = false;
  std::uint64_t commands = 0;  // received so far
};

struct ServoOptions {
  // Between points; empty: the device's floor (its stream period).
  std::optional<Duration> period;
  // A command not renewed for this long counts as stop (MoveIt Servo uses 0.1 s; jog inputs
  // renew theirs at 20 Hz or more).
  Duration command_timeout = std::chrono::milliseconds(200);
  // (0, 1]: every joint's velocity limit is taken times this.
  double speed = 1.0;
  // A twist's linear and angular speed are clipped to these (m/s, rad/s).
  double max_linear_speed = 0.25;
  double max_angular_speed = 1.5;
  // Condition of the Jacobian (arm/servo_twist.hpp condition) where slowing starts and where
  // it reaches zero (MoveIt Servo's defaults).
  double singularity_slow = 17, singularity_stop = 30;
  // Clearance (m) below which the command is slowed, toward 0 at collision_stop (MoveIt
  // Servo slows within 2 cm of the scene).
  double collision_slow = 0.02, collision_stop = 0.003;
  // Following error, read-back interval and live positions as the executor takes them
  // (only those fields are used).
  ExecutorOptions executor;
  // At the start of every cycle: read inputs and send commands (a terminal, a gamepad, a
  // test script on simulated time).
  std::function<void(TimePoint now)> before_cycle;
  // After every point sent.
  std::function<void(const ServoStatus&)> on_cycle;
};

struct ServoReport {
  Duration elapsed{};
  Duration period{};
  std::size_t cycles = 0, commands = 0, reads = 0;
  // Cycles slowed, by reason (ServoSlowdown's order).
  std::array<std::size_t, kServoSlowdowns> slowed{};
  double largest_following_error = 0;  // SI
  int largest_following_joint = -1;
  std::vector<double> positions;  // where it came to rest (SI, every joint)
};

// Runs until `input` finishes and the arm is at rest. Errors: the device's (the arm is
// halted), a following error (detail FollowingError, the arm halted), a start where the arm
// cannot be read.
Result<ServoReport> run_servo(Arm& arm, ServoInput& input, const ServoOptions& options = {});

}  // namespace armctl::arm
