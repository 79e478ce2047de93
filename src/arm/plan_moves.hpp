// The one planner under every app (docs/architecture.md "One motion service"): the moves an
// app was asked for, as value types, planned from where the arm stands into a Plan that the
// runner (arm/run_motion.hpp) plays. Every check happens here, before anything moves: IK
// (the solution nearest where the move before leaves the arm), the joint limits and the
// device's range (ArmKinematics::check_targets), the whole path of a LIN/CIRC run
// (motion/path_check.hpp), the one duration rule (joint_move_duration). Pure: the
// kinematics value in, the plan out; no device, no I/O, so an HTTP thread, a program check
// or a test plans without touching the arm.
//
// The moves: PTP to joints or to a tool pose (optionally through joint waypoints), runs of
// LIN/CIRC blended by their zones into one Cartesian path, a timed joint trajectory (ROS),
// waits and messages (a program's WAIT and PRINT). A LIN that starts where the arm is
// singular (the xArm straight up) is led in by a short joint move along the line.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "arm/arm_kinematics.hpp"
#include "arm/collision_detail.hpp"
#include "arm/motion_executor.hpp"
#include "arm/motion_planning.hpp"
#include "arm/spline_motion.hpp"
#include "core/error.hpp"

namespace armctl::arm {

// PTP: a joint-space move to joint targets (one entry per joint, SI; empty keeps the joint
// where the move before leaves it) or to a tool pose (the IK solution nearest there).
struct PtpMove {
  std::variant<std::vector<std::optional<double>>, CartesianGoal> target;
  std::vector<std::vector<double>> waypoints;  // every joint, SI: passed without stopping
  // The slowest joint at `speed` of its velocity limit (default motion::kDefaultJointSpeed),
  // or all arriving after `duration` s (the one rule: never faster than the arm file
  // allows, joint_move_duration; the piece's note says when it was stretched).
  std::optional<double> speed;
  std::optional<double> duration;
  std::string duration_words = "the duration";  // as the user wrote it, for the note
  double acceleration_scale = 1;  // (0, 1] of the acceleration limits (a program's ACCEL)
  // Streamed: never shorter than this (s; a replay at its recorded pace, Python's
  // min_duration), however fast `speed` would take it.
  double min_duration = 0;
};

// A joint trajectory with its own times (a ROS goal): arm/spline_motion.hpp.
struct TrajectoryMove {
  SplineRequest spline;
};

struct WaitMove {
  double seconds = 0;
};

// Handed to the runner's hooks when the run reaches it (a program's PRINT).
struct MessageMove {
  std::string text;
};

struct Move {
  using What = std::variant<PtpMove, CartesianMove, TrajectoryMove, WaitMove, MessageMove>;
  What what;
  std::string label;  // for messages and progress ("line 12 (LIN)"); empty: "move N"
  std::size_t line = 0, column = 0;  // where a file gave it (0: not from a file)

  Move(What move, std::string for_people = {}, std::size_t at_line = 0, std::size_t at_column = 0)
      : what(std::move(move)), label(std::move(for_people)), line(at_line), column(at_column) {}
};

enum class PtpRun {
  stream,  // host-planned (jerk-limited) and streamed by the executor
  board,   // sent as one move the device interpolates (Arm::send), then waited for
};

struct PlanOptions {
  // Consecutive LIN/CIRC moves are one path (their zones blend the corners). Off: each is
  // its own piece and ends at rest.
  bool blend = true;
  // A LIN starting where the arm is singular: a joint move first takes the tool 30 mm along
  // the line (the line cannot start there).
  bool lead_in = true;
  PathTiming timing;  // a path's accelerations (a move's own acceleration lowers them)
  PtpRun ptp = PtpRun::stream;
};

enum class PieceKind { motion, board_move, wait, message };

struct PlannedPiece {
  PieceKind kind = PieceKind::motion;
  std::size_t first_move = 0, last_move = 0;  // the moves it plays (indices)
  std::size_t first_line = 0, last_line = 0, first_column = 0;  // of those moves
  std::string label;
  PlannedMotion motion;  // motion
  std::shared_ptr<const motion::CartesianPath> path;  // a Cartesian motion
  std::shared_ptr<const motion::CheckedPath> checked;
  std::vector<std::optional<double>> targets;  // board_move: SI per joint (partners of a coupling included)
  double seconds = 0;  // wait, board_move: how long
  std::string text;    // message
  std::string note;    // why it takes longer than asked
  std::size_t moves = 0;  // moves it plays (waits and messages: 0)
  std::vector<double> end;  // every joint (SI) when it ends
  double duration() const { return kind == PieceKind::motion ? motion.duration : kind == PieceKind::message ? 0 : seconds; }
};

struct Plan {
  std::vector<double> start;  // every joint, SI
  std::vector<PlannedPiece> pieces;
  double duration = 0;  // nominal s at 100 %
  std::size_t moves = 0;
  // The smallest clearance between two checked bodies along every motion (docs/scene.md);
  // empty when the arm has no collision model.
  std::optional<scene::Clearance> clearance;
  const std::vector<double>& end() const { return pieces.empty() ? start : pieces.back().end; }
  // The notes of its pieces ("--time 0.1s is too short for ..."), joined by "; ".
  std::string notes() const;
};

// Which moves a refusal is about (a LIN/CIRC run: all of it; the path's error names the
// segment within it). The error itself is the cause's, its kind, message and detail
// unchanged, so that apps map it as they map any other.
struct MoveRefusal {
  std::size_t first_move = 0, last_move = 0;
};


// `refused`, when given, is set to the moves a refusal is about.
Result<Plan> plan_moves(const ArmKinematics& kinematics, const std::vector<double>& from, std::span<const Move> moves,
                        const PlanOptions& options = {}, MoveRefusal* refused = nullptr);

// How long `plan` runs with its motions at `speed_override` (0, 1] of their programmed
// speeds: motions 1/override as long, waits and board moves as planned.
double run_duration(const Plan& plan, double speed_override);

}  // namespace armctl::arm
