#include "program/program_plan.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "core/source_place.hpp"
#include "motion/move_limits.hpp"

namespace armctl::program {

namespace {

// Places the flow's actions one after the other, each planned by arm::plan_moves from where
// the one before ends (a target's offsets and left-out orientations are taken from there).
class Planner {
 public:
  Planner(const arm::ArmKinematics& kinematics, std::vector<double> start, std::string_view source,
          const PlanOptions& options)
      : kin_(kinematics), model_(kinematics.model()), state_(std::move(start)), source_(source), options_(options) {}

  ProgramPlan plan(const Flow& flow) {
    out_.start = state_;
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
        arm::Move m{arm::WaitMove{act.seconds}, fmt::format("line {} (WAIT {:.3g} s)", act.at.line, act.seconds),
                    act.at.line, act.at.column};
        add(act, {m});
      } else {
        arm::Move m{arm::MessageMove{act.text}, fmt::format("line {} (PRINT)", act.at.line), act.at.line,
                    act.at.column};
        add(act, {m});
      }
      ++k;
    }
    return std::move(out_);
  }

 private:
  static std::string what(const Action& a) {
    return fmt::format("line {} ({} {})", a.at.line, to_string(a.move.kind), a.move.target.label);
  }
  // The planner's refusal of the action's move at its line, its detail (a collision's bodies)
  // kept as the place's cause.
  [[noreturn]] void refuse(const Action& a, const Error& e) const {
    throw ArmctlError(source_error(ErrorKind::invalid_argument,
                                   {std::string(source_), a.at.line, 0,
                                    fmt::format("({} {}): {}", to_string(a.move.kind), a.move.target.label, e.message),
                                    e.detail}));
  }
  motion::JointVector chain(const std::vector<double>& q) const { return kin_.chain_of(q); }

  // Plans `moves` from where the plan stands and appends their pieces.
  Result<arm::Plan> plan_from_here(const std::vector<arm::Move>& moves) const {
    return arm::plan_moves(kin_, state_, moves);
  }
  void append(arm::Plan plan) {
    if (plan.clearance && (!out_.clearance || plan.clearance->distance < out_.clearance->distance)) out_.clearance = plan.clearance;
    for (auto& p : plan.pieces) {
      out_.duration += p.duration();
      out_.moves += p.moves;
      out_.pieces.push_back(std::move(p));
    }
    state_ = out_.pieces.empty() ? state_ : out_.pieces.back().end;
  }
  // One action's moves: a refusal names its line.
  void add(const Action& a, const std::vector<arm::Move>& moves) {
    auto plan = plan_from_here(moves);
    if (!plan) refuse(a, plan.error());
    append(std::move(plan).value());
  }

  // The tool pose a target asks for, from the state `from` (orientations left out keep the
  // current ones; `current` is the running orientation of a Cartesian path).
  struct Goal {
    arm::CartesianGoal goal;
    std::optional<std::vector<std::optional<double>>> joints;  // a joint target without an offset
  };
  Goal goal_of(const Action& a, const TargetValue& t, const std::vector<double>& from) const {
    Goal g;
    if (!t.joints.empty()) {
      auto given = arm::joint_values_targets(model_, t.joints);
      if (!given) refuse(a, given.error());
      if (!t.offset_frame) {
        g.joints = std::move(given).value();
        return g;
      }
      std::vector<double> q = from;
      for (std::size_t i = 0; i < q.size(); ++i)
        if ((*given)[i]) q[i] = *(*given)[i];
      const motion::Pose p = kin_.forward(chain(q));
      const motion::Rpy r = kin_.tool_rpy(p, chain(q));
      g.goal.position = p.position;
      g.goal.roll = r.roll;
      g.goal.pitch = r.pitch;
      g.goal.yaw = r.yaw;
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
      const motion::Rpy r = kin_.goal_rpy(g.goal, kin_.tool_rpy_at(from));
      g.goal.roll = r.roll;
      g.goal.pitch = r.pitch;
      g.goal.yaw = r.yaw;
      g.goal.position += motion::from_rpy(r) * t.offset;
    }
    return g;
  }

  void ptp(const Action& a) {
    const Goal g = goal_of(a, a.move.target, state_);
    arm::PtpMove move;
    if (g.joints) move.target = *g.joints;
    else move.target = g.goal;
    // The flow checked the speed and the OVERRIDE, each in its range; their product is held
    // to the slowest any move runs (motion/move_limits.hpp), as it is for LIN/CIRC below.
    move.speed = std::clamp(a.move.speed.value_or(motion::kDefaultJointSpeed) * a.move.override_fraction,
                            motion::kMinSpeedFraction, motion::kMaxSpeedFraction);
    move.acceleration_scale = a.move.acceleration.value_or(1.0);
    if (options_.avoid) {
      auto around = arm::avoiding_move(kin_, state_, move, *options_.avoid);
      if (!around) refuse(a, around.error());
      move = around->move;
    }
    add(a, {arm::Move{move, what(a), a.at.line, a.at.column}});
  }

  void gripper(const Action& a) {
    if (!model_.gripper)
      throw ArmctlError(source_error(ErrorKind::invalid_argument, {std::string(source_), a.at.line, 0,
                                                                   fmt::format("GRIPPER: arm '{}' has no gripper", model_.name)}));
    std::vector<std::optional<double>> target(state_.size());
    target[std::size_t(model_.gripper->joint)] = model_.gripper->at(a.closed_fraction);
    arm::PtpMove move;
    move.target = target;
    move.speed = kGripperSpeed;
    Action as_move = a;
    as_move.move.kind = MoveKind::ptp;
    as_move.move.target.label = fmt::format("gripper {:.0f} % closed", a.closed_fraction * 100);
    add(as_move, {arm::Move{move, fmt::format("line {} (GRIPPER {:.0f} % closed)", a.at.line, a.closed_fraction * 100),
                            a.at.line, a.at.column}});
  }

  void cartesian(const std::vector<Action>& a, std::size_t from, std::size_t to) {
    std::vector<arm::Move> moves;
    for (std::size_t k = from; k < to; ++k) {
      const MoveAction& m = a[k].move;
      // Offsets and orientations left out are taken from where the previous move ends:
      // the planned end of the segment before, whose joints are known only after the check,
      // so the running orientation stands in (the position of a tool offset needs it).
      arm::CartesianMove t;
      t.kind = m.kind == MoveKind::circ ? motion::SegmentKind::circ : motion::SegmentKind::lin;
      t.goal = goal_of(a[k], m.target, state_).goal;
      if (m.via) t.via = goal_of(a[k], *m.via, state_).goal.position;
      t.speed = std::max(m.speed.value_or(motion::kDefaultToolSpeed) * m.override_fraction, motion::kMinToolSpeed);
      t.angular_speed = std::max(m.angular_speed.value_or(motion::kDefaultToolAngularSpeed) * m.override_fraction,
                                 motion::kMinToolAngularSpeed);
      t.zone = m.zone;
      t.acceleration = m.acceleration;
      moves.push_back({t, what(a[k]), a[k].at.line, a[k].at.column});
    }
    auto plan = plan_from_here(moves);
    if (!plan) refuse_path(a, from, to, plan.error());
    if (to - from > 1) {
      arm::PlannedPiece& p = plan->pieces.back();
      p.label = fmt::format("line {} ({}) .. line {} ({})", a[from].at.line, to_string(a[from].move.kind),
                            a[to - 1].at.line, to_string(a[to - 1].move.kind));
    }
    append(std::move(plan).value());
  }

  // A path's refusal names the segment within the stretch (motion::PathRefusal): say which
  // line of the program that is. A joint move leading in (off a singular start) is refused
  // as the run's first move.
  [[noreturn]] void refuse_path(const std::vector<Action>& a, std::size_t from, std::size_t to, const Error& e) const {
    const motion::PathRefusal* r = motion::path_refusal_of(e);
    if (r && r->segment >= 0 && std::size_t(r->segment) < to - from) {
      const Action& at = a[from + std::size_t(r->segment)];
      throw ArmctlError(source_error(e.kind, {std::string(source_), at.at.line, 0,
                                              fmt::format("({} {}): {}", to_string(at.move.kind),
                                                          at.move.target.label, r->reason)}));
    }
    throw ArmctlError(source_error(e.kind, {std::string(source_), a[from].at.line, 0, e.message, e.detail}));
  }

  const arm::ArmKinematics& kin_;
  const arm::ArmModel& model_;
  std::vector<double> state_;
  std::string_view source_;
  PlanOptions options_;
  ProgramPlan out_;
};

}  // namespace

Result<ProgramPlan> plan_program(const arm::ArmKinematics& kinematics, const std::vector<double>& start,
                                 const Flow& flow, std::string_view source, const PlanOptions& options) {
  if (start.size() != std::size_t(kinematics.joint_count()))
    return Error{ErrorKind::invalid_argument, fmt::format("the start has {} joint values; arm '{}' has {} joints",
                                                          start.size(), kinematics.model().name,
                                                          kinematics.joint_count())};
  return catch_error([&]() -> Result<ProgramPlan> { return Planner(kinematics, start, source, options).plan(flow); });
}

}  // namespace armctl::program
