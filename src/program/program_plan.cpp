#include "program/program_plan.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "core/source_place.hpp"

namespace armctl::program {

namespace {

class Planner {
 public:
  Planner(const arm::Arm& arm, std::vector<double> start, std::string_view source, const PlanOptions& options)
      : arm_(arm), model_(arm.model()), state_(std::move(start)), source_(source), options_(options) {}

  ProgramPlan plan(const Flow& flow) {
    ProgramPlan out;
    out.start = state_;
    const auto& a = flow.actions;
    for (std::size_t k = 0; k < a.size();) {
      const Action& act = a[k];
      if (act.kind == ActionKind::move && act.move.kind != MoveKind::ptp) {
        std::size_t end = k + 1;
        if (options_.blend)
          while (end < a.size() && a[end].kind == ActionKind::move && a[end].move.kind != MoveKind::ptp) ++end;
        cartesian(a, k, end);
        k = end;
        continue;
      }
      if (act.kind == ActionKind::move) ptp(act);
      else if (act.kind == ActionKind::gripper) gripper(act);
      else if (act.kind == ActionKind::wait) {
        PlannedPiece p;
        p.kind = PieceKind::wait;
        p.first_line = p.last_line = act.at.line;
        p.first_column = act.at.column;
        p.label = fmt::format("line {} (WAIT {:.3g} s)", act.at.line, act.seconds);
        p.seconds = act.seconds;
        p.end = state_;
        pieces_.push_back(std::move(p));
      } else {
        PlannedPiece p;
        p.kind = PieceKind::print;
        p.first_line = p.last_line = act.at.line;
        p.first_column = act.at.column;
        p.label = fmt::format("line {} (PRINT)", act.at.line);
        p.text = act.text;
        p.end = state_;
        pieces_.push_back(std::move(p));
      }
      ++k;
    }
    for (auto& p : pieces_) {
      out.duration += p.kind == PieceKind::motion ? p.motion.duration : p.seconds;
      out.moves += p.moves;
    }
    out.pieces = std::move(pieces_);
    return out;
  }

 private:
  static std::string what(const Action& a) {
    return fmt::format("line {} ({} {})", a.at.line, to_string(a.move.kind), a.move.target.label);
  }
  [[noreturn]] void refuse(const Action& a, const std::string& why) const {
    throw ArmctlError(source_error(ErrorKind::invalid_argument,
                                   {std::string(source_), a.at.line, 0,
                                    fmt::format("({} {}): {}", to_string(a.move.kind), a.move.target.label, why)}));
  }
  motion::JointVector chain(const std::vector<double>& q) const { return arm_.chain_of(q); }

  // The tool pose a target asks for, from the state `from` (orientations left out keep the
  // current ones; `current` is the running orientation of a Cartesian path).
  struct Goal {
    arm::CartesianGoal goal;
    std::optional<std::vector<double>> joints;  // a joint target without an offset
  };
  Goal goal_of(const Action& a, const TargetValue& t, const std::vector<double>& from) const {
    Goal g;
    if (!t.joints.empty()) {
      auto given = arm::joint_values_target(model_, from, t.joints);
      if (!given) refuse(a, given.error().message);
      const std::vector<double> q = std::move(given).value();
      const motion::Pose p = arm_.forward(chain(q));
      const motion::Rpy r = arm_.tool_rpy(p, chain(q));
      g.goal.position = p.position;
      g.goal.roll = r.roll;
      g.goal.pitch = r.pitch;
      g.goal.yaw = r.yaw;
      if (!t.offset_frame) {
        g.joints = q;
        return g;
      }
    } else {
      g.goal.position = t.position;
      g.goal.roll = t.roll;
      g.goal.pitch = t.pitch;
      g.goal.yaw = t.yaw;
      g.goal.elbow = t.elbow;
    }
    if (t.offset_frame == OffsetFrame::base) {
      g.goal.position += t.offset;
    } else if (t.offset_frame == OffsetFrame::tool) {
      const motion::JointVector qc = chain(from);
      const motion::Rpy r = arm_.goal_rpy(g.goal, arm_.tool_rpy(arm_.forward(qc), qc));
      g.goal.roll = r.roll;
      g.goal.pitch = r.pitch;
      g.goal.yaw = r.yaw;
      g.goal.position += motion::from_rpy(r) * t.offset;
    }
    return g;
  }

  void joint_piece(const Action& a, const std::vector<double>& target, double speed, std::optional<double> accel,
                   const std::string& label) {
    std::vector<std::optional<double>> check(target.begin(), target.end());
    if (auto ok = arm_.check_targets(check); !ok) refuse(a, ok.error().message);
    arm::ArmModel scaled;
    const arm::ArmModel* model = &model_;
    if (accel) {
      scaled = model_;
      for (auto& j : scaled.joints) j.limits.acceleration *= *accel;
      model = &scaled;
    }
    arm::JointMove move;
    move.target = target;
    move.speed = speed;
    auto planned = arm::plan_joint_move(*model, state_, move);
    if (!planned) refuse(a, planned.error().message);
    PlannedPiece p;
    p.first_line = p.last_line = a.at.line;
    p.first_column = a.at.column;
    p.label = label;
    p.motion = std::move(planned).value();
    p.moves = 1;
    p.end = target;
    pieces_.push_back(std::move(p));
    state_ = target;
  }

  void ptp(const Action& a) {
    const Goal g = goal_of(a, a.move.target, state_);
    std::vector<double> target = state_;
    if (g.joints) {
      target = *g.joints;
    } else {
      arm::JointState now;
      now.positions = state_;
      auto solutions = arm_.inverse(g.goal, now);
      if (!solutions) refuse(a, solutions.error().message);
      const motion::JointVector& q = solutions->front().joints;
      for (int i = 0; i < q.size(); ++i) target[std::size_t(i)] = q[i];
    }
    // The flow checked the speed and the OVERRIDE, each in its range; their product is held
    // to the slowest any move runs (motion/move_limits.hpp), as it is for LIN/CIRC below.
    const double speed = std::clamp(a.move.speed.value_or(kDefaultPtpSpeed) * a.move.override_fraction,
                                    motion::kMinSpeedFraction, motion::kMaxSpeedFraction);
    joint_piece(a, target, speed, a.move.acceleration, what(a));
  }

  void gripper(const Action& a) {
    if (!model_.gripper)
      throw ArmctlError(source_error(ErrorKind::invalid_argument, {std::string(source_), a.at.line, 0,
                                                                   fmt::format("GRIPPER: arm '{}' has no gripper", model_.name)}));
    std::vector<double> target = state_;
    target[std::size_t(model_.gripper->joint)] = model_.gripper->at(a.closed_fraction);
    Action as_move = a;
    as_move.move.kind = MoveKind::ptp;
    as_move.move.target.label = fmt::format("gripper {:.0f} % closed", a.closed_fraction * 100);
    joint_piece(as_move, target, kGripperSpeed, std::nullopt,
                fmt::format("line {} (GRIPPER {:.0f} % closed)", a.at.line, a.closed_fraction * 100));
  }

  void cartesian(const std::vector<Action>& a, std::size_t from, std::size_t to) {
    std::vector<arm::CartesianMove> targets;
    double acceleration = kDefaultPathAcceleration;
    for (std::size_t k = from; k < to; ++k) {
      const MoveAction& m = a[k].move;
      // Offsets and orientations left out are taken from where the previous move ends:
      // the planned end of the segment before, whose joints are known only after the check,
      // so the running orientation stands in (the position of a tool offset needs it).
      arm::CartesianMove t;
      t.kind = m.kind == MoveKind::circ ? motion::SegmentKind::circ : motion::SegmentKind::lin;
      t.goal = goal_of(a[k], m.target, state_).goal;
      if (m.via) t.via = goal_of(a[k], *m.via, state_).goal.position;
      t.speed = std::max(m.speed.value_or(arm::kDefaultPathSpeed) * m.override_fraction, motion::kMinToolSpeed);
      t.angular_speed = std::max(m.angular_speed.value_or(arm::kDefaultAngularSpeed) * m.override_fraction,
                                 motion::kMinToolAngularSpeed);
      t.zone = m.zone;
      if (m.acceleration) acceleration = std::min(acceleration, *m.acceleration);
      targets.push_back(t);
    }
    const std::vector<motion::PathSegment> segments = arm::path_segments(arm_, state_, targets);
    arm::PathTiming timing;
    timing.acceleration = acceleration;
    auto plan = arm::plan_path(model_, state_, segments, timing);
    if (!plan) refuse_path(a, from, to, plan.error());
    const motion::JointVector& end = plan->checked->joints.back();
    for (int i = 0; i < end.size(); ++i) state_[std::size_t(i)] = end[i];
    PlannedPiece p;
    p.first_line = a[from].at.line;
    p.first_column = a[from].at.column;
    p.last_line = a[to - 1].at.line;
    p.label = from + 1 == to ? what(a[from])
                             : fmt::format("line {} ({}) .. line {} ({})", a[from].at.line, to_string(a[from].move.kind),
                                           a[to - 1].at.line, to_string(a[to - 1].move.kind));
    p.motion = std::move(plan->motion);
    p.path = plan->path;
    p.moves = to - from;
    p.end = state_;
    pieces_.push_back(std::move(p));
  }

  // A path's refusal names the segment within the stretch (motion::PathRefusal): say which
  // line of the program that is.
  [[noreturn]] void refuse_path(const std::vector<Action>& a, std::size_t from, std::size_t to, const Error& e) const {
    const motion::PathRefusal* r = motion::path_refusal_of(e);
    if (r && r->segment >= 0 && std::size_t(r->segment) < to - from) {
      const Action& at = a[from + std::size_t(r->segment)];
      throw ArmctlError(source_error(e.kind, {std::string(source_), at.at.line, 0,
                                              fmt::format("({} {}): {}", to_string(at.move.kind),
                                                          at.move.target.label, r->reason)}));
    }
    throw ArmctlError(source_error(e.kind, {std::string(source_), a[from].at.line, 0, e.message}));
  }

  const arm::Arm& arm_;
  const arm::ArmModel& model_;
  std::vector<double> state_;
  std::string_view source_;
  PlanOptions options_;
  std::vector<PlannedPiece> pieces_;
};

}  // namespace

Result<ProgramPlan> plan_program(const arm::Arm& arm, const std::vector<double>& start, const Flow& flow,
                                 std::string_view source, const PlanOptions& options) {
  if (start.size() != std::size_t(arm.model().joint_count()))
    return Error{ErrorKind::invalid_argument, fmt::format("the start has {} joint values; arm '{}' has {} joints",
                                                          start.size(), arm.model().name, arm.model().joint_count())};
  return catch_error([&]() -> Result<ProgramPlan> { return Planner(arm, start, source, options).plan(flow); });
}

double estimated_duration(const ProgramPlan& plan, double speed_override) {
  double total = 0;
  for (const PlannedPiece& p : plan.pieces)
    total += p.kind == PieceKind::motion ? p.motion.duration / speed_override : p.seconds;
  return total;
}

}  // namespace armctl::program
