// Running a program's flow: variables, IF, loops, subroutine calls, evaluated to the
// sequence of actions it performs (moves with their numbers, waits, gripper, prints).
// The language has no run-time inputs, so this sequence is known before anything moves:
// `program check` plans every move of it, `program run` runs it, `program compile` turns
// it into an action group. Bounded: every loop by kMaxLoopIterations, the whole flow by
// the limits below (errors name the statement). Pure code.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/error.hpp"
#include "motion/kinematics.hpp"
#include "files/path_file.hpp"
#include "files/points_file.hpp"
#include "program/program_syntax.hpp"

namespace armctl::program {

struct FlowLimits {
  std::size_t loop_iterations = 10'000;  // per LOOP or WHILE, each time it is entered
  std::size_t statements = 1'000'000;    // statements run in all
  std::size_t actions = 10'000;          // moves, waits, gripper moves and prints in all
  std::size_t call_depth = 64;           // subroutines calling subroutines
};

// A move's target with its numbers, not yet placed on an arm (that needs where the arm is:
// program_plan.hpp).
struct TargetValue {
  std::string label;  // "pick", "pick + tool(0, 0, -30 mm)", "pose(...)", "joints(...)"
  std::vector<files::JointValue> joints;  // a joint target, or empty for a pose
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::optional<double> roll, pitch, yaw;
  std::optional<motion::Elbow> elbow;
  std::optional<OffsetFrame> offset_frame;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // m
};

struct MoveAction {
  MoveKind kind = MoveKind::ptp;
  TargetValue target;
  std::optional<TargetValue> via;  // circ
  std::optional<double> speed;          // ptp: fraction (0, 1]; lin/circ: m/s
  std::optional<double> acceleration;   // ptp: fraction (0, 1]; lin/circ: m/s^2
  std::optional<double> angular_speed;  // rad/s
  double zone = 0;                      // m
  double override_fraction = 1;         // the OVERRIDE in force, (0, 1]
};

enum class ActionKind { move, wait, gripper, print };

struct Action {
  ActionKind kind = ActionKind::move;
  Place at;
  MoveAction move;
  double seconds = 0;          // wait
  double closed_fraction = 0;  // gripper: 0 open .. 1 closed
  std::string text;            // print
};

struct Flow {
  std::vector<Action> actions;
  std::size_t statements = 0;  // statements run
};

// Names that must resolve before anything runs: every point a move names is in `points`,
// every CALL names a DEF with as many parameters. Errors name the place.
Status check_names(const Program& program, const files::PointsFile& points);

// check_names, then runs the flow. Errors (invalid_config for the program's text,
// invalid_argument for values: a length where a time is wanted, a division by zero, a
// loop past its cap) name "file:line:column:".
Result<Flow> run_flow(const Program& program, const files::PointsFile& points, const FlowLimits& limits = {});

}  // namespace armctl::program
