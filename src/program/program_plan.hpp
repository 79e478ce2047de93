// The check of a program before anything moves: every action of its flow placed on the
// arm from where the previous one ends (the first from where the arm stands), every move
// planned by the motion layer (arm::plan_joint_move, arm::plan_path: reachable and inside
// the joint limits along its whole path) and timed. Consecutive LIN/CIRC moves with
// nothing else between them are one Cartesian path (their zones blend the corners); a
// PTP, WAIT, GRIPPER or PRINT ends it. Pure planning on the Arm API's const calls: no I/O.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "arm/arm.hpp"
#include "arm/motion_planning.hpp"
#include "core/error.hpp"
#include "program/program_flow.hpp"

namespace armctl::program {

// LIN and CIRC without SPEED: arm::kDefaultPathSpeed and kDefaultAngularSpeed.
inline constexpr double kDefaultPtpSpeed = 0.25;                   // of the joints' velocity limits
inline constexpr double kDefaultPathAcceleration = 0.5;            // m/s^2
inline constexpr double kGripperSpeed = 0.5;                       // of the gripper's velocity limit

struct PlanOptions {
  // Blend consecutive LIN/CIRC moves into one path. Off (--step): every move is its own
  // piece and ends at rest (zones are then not used).
  bool blend = true;
};

enum class PieceKind { motion, wait, print };

struct PlannedPiece {
  PieceKind kind = PieceKind::motion;
  std::size_t first_line = 0, last_line = 0;
  std::size_t first_column = 0;  // of the statement on first_line (1-based)
  std::string label;  // "line 12 (LIN pick + tool(...))", "line 12 (LIN) .. line 14 (CIRC)"
  arm::PlannedMotion motion;  // motion
  std::shared_ptr<const motion::CartesianPath> path;  // Cartesian pieces
  std::size_t moves = 0;      // program moves in this piece (gripper moves count)
  double seconds = 0;         // wait
  std::string text;           // print
  std::vector<double> end;    // every joint (SI) when the piece ends
};

struct ProgramPlan {
  std::vector<PlannedPiece> pieces;
  std::vector<double> start;  // every joint, SI: where the plan starts
  double duration = 0;        // s at 100 %: motions and waits
  std::size_t moves = 0;
};

// How long the plan runs with every motion at `speed_override` (0..1] of its programmed
// speeds: the motions take 1/override as long, the waits as long as written.
double estimated_duration(const ProgramPlan& plan, double speed_override);

// Errors (invalid_argument) start with "file:line: (KIND target): " and say why: no IK
// solution, outside a joint's limits (which joint, where), a CIRC's three points on a line.
Result<ProgramPlan> plan_program(const arm::Arm& arm, const std::vector<double>& start, const Flow& flow,
                                 std::string_view source, const PlanOptions& options = {});

}  // namespace armctl::program
