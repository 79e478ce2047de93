// The one runner under every app (docs/architecture.md "One motion service"): plays a Plan
// (arm/plan_moves.hpp) on the arm from where it stands (the plan's start): streamed
// motions through the executor (arm/motion_executor.hpp), board moves sent and waited for,
// waits on the device's clock, messages handed to the app; at the end it waits for the arm
// to arrive at the last point. Stop, pause and resume come through `command`, progress and
// reports go out through the hooks: what differs per app (CLI progress lines, Python's
// Ctrl-C, ROS feedback, the web job's state) is in the hooks, never in here.
#pragma once

#include <functional>
#include <optional>

#include "arm/arm.hpp"
#include "arm/motion_executor.hpp"
#include "arm/plan_moves.hpp"
#include "core/error.hpp"

namespace armctl::arm {

enum class RunEventKind { piece_started, progress, piece_done, message };

struct RunEvent {
  RunEventKind kind = RunEventKind::piece_started;
  const PlannedPiece* piece = nullptr;
  double done = 0;  // nominal s of the plan behind us
  double left = 0;  // s left at the override
  const MotionReport* report = nullptr;  // piece_done of a streamed motion
};

struct RunHooks {
  double speed_override = 1.0;  // (0, 1]: streamed motions only (a wait is a time)
  // Asked before every stream point and every 20 ms of a wait or a board move: stop ends
  // the run at rest (a streamed motion slows down on its path), pause/resume hold it.
  std::function<MotionCommand()> command;
  // Before each motion or board move (a step-by-step run): false stops the run there.
  std::function<bool(const PlannedPiece&)> before_piece;
  // Pieces started and done, progress (every `progress_every` of device time), messages.
  std::function<void(const RunEvent&)> on_event;
  Duration progress_every = std::chrono::milliseconds(250);
  // The base of every streamed motion's executor options (following error, position
  // publishing, an arm worker's pause/stop commands: session::JobContext::executor_options)
  // and of the waits for arrival (timeout, tolerances, interruption).
  ExecutorOptions executor;
  WaitOptions wait;
  // Wait for the arm to arrive after the last piece (board moves: after each one). Off: a
  // board move returns once sent (the app waits itself, or not).
  bool wait_for_arrival = true;
  // Errors of a piece start with its label ("line 12 (LIN pick): ...").
  bool label_errors = false;
  // The error when the arm does not arrive at the end (Arm::wait's timeout naming each late
  // joint) as the app says it (a ROS goal tolerance); empty: as it is. Not for a stall
  // (detail JointStall), which keeps its own.
  std::function<Error(const Error&)> not_arrived;
};

struct RunReport {
  bool completed = false;  // every piece ran to its end
  bool stopped = false;    // by a stop command (at rest; on the path when streaming)
  std::size_t pieces = 0;  // pieces run to their end
  Duration elapsed{};
  double t_reached = 0;  // nominal s of the plan where it ended
  double largest_following_error = 0;  // SI, over every joint and read-back
  int largest_following_joint = -1;
  std::optional<MotionReport> last_motion;  // of the last streamed piece
  std::optional<JointState> arrived;        // the read that found the arm arrived
};

// The plan must start where the arm stands (plan it from a fresh read). Errors: the
// executor's (a following error names the joint), the device's, a wait's (the arm did not
// arrive: timeout naming each late joint). A stop asked while waiting is not an error:
// the report says stopped (a board move is halted where the arm is, Arm::stop).
Result<RunReport> run_motion(Arm& arm, const Plan& plan, const RunHooks& hooks = {});

}  // namespace armctl::arm
