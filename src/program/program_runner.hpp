// Runs a checked program plan on an arm: every motion piece through the motion executor
// (arm/motion_executor.hpp), waits on the device's clock, prints handed to the caller.
// The caller's `command` can stop at any point: a motion then slows down on its path
// within the joints' limits (the executor's stop) and the run ends there.
#pragma once

#include <functional>
#include <string>

#include "arm/arm.hpp"
#include "arm/motion_executor.hpp"
#include "core/error.hpp"
#include "program/program_plan.hpp"

namespace armctl::program {

enum class RunEventKind { piece_started, progress, piece_done, print };

struct RunEvent {
  RunEventKind kind = RunEventKind::piece_started;
  const PlannedPiece* piece = nullptr;
  double done = 0;  // nominal s of the plan behind us
  double left = 0;  // s left at the override
  const arm::MotionReport* report = nullptr;  // piece_done of a motion
};

struct RunOptions {
  double speed_override = 1.0;  // (0, 1]: motions only (a WAIT is a time)
  // Asked before every stream point and every 20 ms of a wait: stop ends the run at rest.
  std::function<arm::MotionCommand()> command;
  // Before each motion piece (--step): false stops the run there.
  std::function<bool(const PlannedPiece&)> before_motion;
  std::function<void(const RunEvent&)> on_event;
  // The base of every motion's executor options and of the final wait (an arm worker's
  // JobContext wires its pause/stop commands and position publishing here): run_plan sets
  // the override and adds `command` and its progress events on top.
  arm::ExecutorOptions executor;
  arm::WaitOptions wait;
};

struct RunReport {
  bool completed = false;  // every piece ran to its end
  std::size_t pieces = 0;  // pieces run (to their end)
  Duration elapsed{};
  double largest_following_error = 0;  // SI, over every joint and read-back
};

// The plan must start where the arm stands (plan it from a fresh read). Errors: the
// executor's and the device's, prefixed with the piece ("line 12 (LIN pick): ...").
Result<RunReport> run_plan(arm::Arm& arm, const ProgramPlan& plan, const RunOptions& options = {});

}  // namespace armctl::program
