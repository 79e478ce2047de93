// The check of a program before anything moves: every action of its flow placed on the
// arm from where the previous one ends (the first from where the arm stands), every move
// planned by the one planner (arm::plan_moves: reachable and inside the joint limits and
// the device's range along its whole path) and timed. Consecutive LIN/CIRC moves with
// nothing else between them are one Cartesian path (their zones blend the corners); a
// PTP, WAIT, GRIPPER or PRINT ends it. Pure planning on the arm's kinematics: no device.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "arm/arm_kinematics.hpp"
#include "arm/avoid_path.hpp"
#include "arm/plan_moves.hpp"
#include "core/error.hpp"
#include "program/program_flow.hpp"

namespace armctl::program {

// A GRIPPER statement's speed; PTP, LIN and CIRC without SPEED and ACCEL take the motion
// layer's defaults (motion/move_limits.hpp).
inline constexpr double kGripperSpeed = motion::kDefaultGripperSpeed;  // of the gripper's velocity limit

struct PlanOptions {
  // Blend consecutive LIN/CIRC moves into one path. Off (--step): every move is its own
  // piece and ends at rest (zones are then not used).
  bool blend = true;
  // PTPs whose direct motion would collide go around the obstacles (arm/avoid_path.hpp,
  // docs/scene.md "Around obstacles"); each gets this budget.
  std::optional<arm::AvoidOptions> avoid;
};

// A program's plan is the planner's (arm/plan_moves.hpp): its pieces' lines are the
// statements', WAIT is a wait piece and PRINT a message piece.
using PieceKind = arm::PieceKind;
using PlannedPiece = arm::PlannedPiece;
using ProgramPlan = arm::Plan;

// How long the plan runs with every motion at `speed_override` (0..1] of its programmed
// speeds: the motions take 1/override as long, the waits as long as written.
inline double estimated_duration(const ProgramPlan& plan, double speed_override) {
  return arm::run_duration(plan, speed_override);
}

// Errors (invalid_argument) start with "file:line: (KIND target): " and say why: no IK
// solution, outside a joint's limits (which joint, where), a CIRC's three points on a line.
Result<ProgramPlan> plan_program(const arm::ArmKinematics& kinematics, const std::vector<double>& start,
                                 const Flow& flow, std::string_view source, const PlanOptions& options = {});

}  // namespace armctl::program
