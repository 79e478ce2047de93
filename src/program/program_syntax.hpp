// The syntax tree of a robot program (docs/programs.md): what program_parser produces and
// program_flow runs. Plain values; every node keeps its line and column for messages.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "program/program_values.hpp"

namespace armctl::program {

struct Place {
  std::size_t line = 0, column = 0;  // 1-based
};

// ---------------------------------------------------------------- expressions
struct Expr;
using ExprPtr = std::unique_ptr<Expr>;

enum class ExprKind { number, variable, unary, binary };
enum class Operator { add, sub, mul, div, neg, lt, le, gt, ge, eq, ne, and_, or_, not_ };
const char* to_string(Operator op);  // as written: "+", "<=", "and", ...

struct Expr {
  Expr() = default;
  Expr(const Expr&) = delete;
  Expr& operator=(const Expr&) = delete;
  // Frees the children by a loop, not by recursion: a long chain (a + b + c ...) is a
  // left-deep tree, and freeing it node by node recursively would exhaust the stack.
  ~Expr();

  ExprKind kind = ExprKind::number;
  Place at;
  Value value;       // number
  std::string name;  // variable
  Operator op = Operator::add;
  ExprPtr left, right;  // unary: left only
};

// ---------------------------------------------------------------- move targets
enum class TargetKind { point, pose, joints };
enum class OffsetFrame { tool, base };

struct Field {  // name=expr (pose fields, offsets, move options), or elbow=up
  std::string name;
  Place at;
  ExprPtr value;        // empty for elbow
  std::string word;     // elbow's value
};

struct Target {
  TargetKind kind = TargetKind::point;
  Place at;
  std::string point;               // point
  std::vector<Field> pose;         // pose(x=.., y=.., z=.., roll=.., pitch=.., yaw=.., elbow=..)
  std::vector<ExprPtr> joints;     // joints(v1, v2, ...)
  std::optional<OffsetFrame> offset_frame;  // + tool(...) / + base(...)
  std::vector<Field> offset;       // x, y, z (lengths): a translation
};

// ---------------------------------------------------------------- statements
struct Statement;
using Block = std::vector<Statement>;

enum class StatementKind { move, wait, gripper, print, assign, if_, loop, while_, call, override_ };
enum class MoveKind { ptp, lin, circ };
const char* to_string(MoveKind kind);  // "PTP", "LIN", "CIRC"
enum class GripperAction { open, close, to };

struct PrintItem {
  std::optional<std::string> text;  // a string, or
  ExprPtr value;                    // an expression
};

struct Statement {
  StatementKind kind = StatementKind::move;
  Place at;
  // move
  MoveKind move = MoveKind::ptp;
  std::optional<Target> via;  // circ
  Target target;
  std::vector<Field> options;  // speed, accel, zone, angular_speed
  // wait, gripper (to), assign, if, loop (count), while, override
  ExprPtr value;
  GripperAction gripper = GripperAction::open;
  std::string name;  // assign: the variable; call: the subroutine
  std::vector<PrintItem> print;
  std::vector<ExprPtr> arguments;  // call
  Block body, otherwise;           // if / loops: body; if: else
};

struct Subroutine {
  std::string name;
  Place at;
  std::vector<std::string> parameters;
  Block body;
};

struct Program {
  std::string source;  // the file's name, for messages
  std::vector<Subroutine> subroutines;
  Block main;  // the statements outside any DEF, in order
};

}  // namespace armctl::program
