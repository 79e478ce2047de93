#include "apps/armctl/arm_motion.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "apps/armctl/json_output.hpp"
#include "apps/armctl/motion_trace.hpp"
#include "apps/armctl/serve_support.hpp"
#include "arm/motion_executor.hpp"
#include "arm/motion_planning.hpp"
#include "core/quantity.hpp"

namespace armctl::cli {

namespace {

using nlohmann::json;

constexpr double kDefaultPtpSpeed = 0.25;                 // of the velocity limits

// Where a move came from, for messages: "line 12" of a path file, or the command line.
std::string where(const motion::PathMove& m) {
  return m.line ? fmt::format("line {} ({})", m.line, motion::to_string(m.kind)) : std::string("the move");
}

[[noreturn]] void refuse_at(const motion::PathMove& m, const std::string& why) {
  throw ArmctlError(ErrorKind::invalid_argument, fmt::format("{}: {}", where(m), why));
}

// One planned piece and the line it starts at.
struct Piece {
  std::size_t line = 0;
  std::string label;
  arm::PlannedMotion motion;
  std::shared_ptr<const motion::CartesianPath> path;  // Cartesian pieces
};

class Planner {
 public:
  Planner(arm::Arm& arm, std::vector<double> start) : arm_(arm), model_(arm.model()), state_(std::move(start)) {}

  std::vector<Piece> plan(const std::vector<motion::PathMove>& moves) {
    for (std::size_t k = 0; k < moves.size();) {
      if (moves[k].kind == motion::MoveKind::ptp) {
        plan_ptp(moves[k]);
        ++k;
        continue;
      }
      std::size_t end = k;
      while (end < moves.size() && moves[end].kind != motion::MoveKind::ptp) ++end;
      plan_cartesian(moves, k, end);
      k = end;
    }
    return std::move(pieces_);
  }

 private:

  void plan_ptp(const motion::PathMove& m) {
    std::vector<double> target = state_;
    if (!m.joints.empty()) {
      auto given = arm::joint_values_target(model_, state_, m.joints);
      if (!given) refuse_at(m, given.error().message);
      target = std::move(given).value();
    } else {
      arm::CartesianGoal goal = goal_of(m);
      goal.elbow = m.elbow;
      arm::JointState now;
      now.positions = state_;
      auto solutions = arm_.inverse(goal, now);
      if (!solutions) refuse_at(m, solutions.error().message);
      const motion::JointVector& q = solutions->front().joints;
      for (int i = 0; i < q.size(); ++i) target[std::size_t(i)] = q[i];
    }
    std::vector<std::optional<double>> check(target.begin(), target.end());
    if (auto ok = arm_.check_targets(check); !ok) refuse_at(m, ok.error().message);
    arm::JointMove move;
    move.target = target;
    move.speed = m.speed_fraction.value_or(kDefaultPtpSpeed);
    auto planned = arm::plan_joint_move(model_, state_, move);
    if (!planned) refuse_at(m, planned.error().message);
    pieces_.push_back({m.line, where(m), std::move(planned).value(), nullptr});
    state_ = target;
  }

  arm::CartesianGoal goal_of(const motion::PathMove& m) const {
    arm::CartesianGoal g;
    g.position = m.position;
    g.roll = m.roll;
    g.pitch = m.pitch;
    g.yaw = m.yaw;
    return g;
  }

  void plan_cartesian(const std::vector<motion::PathMove>& moves, std::size_t from, std::size_t to) {
    std::vector<arm::CartesianMove> targets;
    for (std::size_t k = from; k < to; ++k) {
      const motion::PathMove& m = moves[k];
      arm::CartesianMove t;
      t.kind = m.kind == motion::MoveKind::circ ? motion::SegmentKind::circ : motion::SegmentKind::lin;
      t.goal = goal_of(m);
      t.via = m.via;
      t.speed = m.speed.value_or(arm::kDefaultPathSpeed);
      t.angular_speed = m.angular_speed.value_or(arm::kDefaultAngularSpeed);
      t.zone = m.zone;
      targets.push_back(t);
    }
    std::vector<motion::PathSegment> segments = arm::path_segments(arm_, state_, targets);
    auto plan = arm::plan_path(model_, state_, segments);
    if (!plan)
      if (auto led = lead_in(moves[from], segments.front(), targets)) plan = std::move(*led);
    if (!plan) {
      // The path's errors count segments from 1 within this stretch: say which lines.
      const std::string lines = moves[from].line
                                    ? fmt::format("lines {}..{}: ", moves[from].line, moves[to - 1].line)
                                    : std::string();
      throw ArmctlError(plan.error().kind, lines + plan.error().message);
    }
    const motion::JointVector& end = plan->checked->joints.back();
    for (int i = 0; i < end.size(); ++i) state_[std::size_t(i)] = end[i];
    pieces_.push_back({moves[from].line, from + 1 == to ? where(moves[from])
                                                         : fmt::format("{} .. {}", where(moves[from]), where(moves[to - 1])),
                       std::move(plan->motion), plan->path});
  }

  // A line cannot start where the arm is singular (the xArm straight up, as it starts:
  // motion::kSingularStart). So a joint move (PTP) first takes the tool kLeadIn along the
  // line, with the orientation the move asks (the xArm's pitch free), and the line goes on
  // from there: the plan of the line, with the joint move's piece before it, in the first
  // elbow configuration from which the line plans. Empty (nothing planned) when the arm is
  // not at a singularity, the line is too short or plans from no configuration.
  std::optional<arm::PathPlan> lead_in(const motion::PathMove& m, const motion::PathSegment& first,
                                       const std::vector<arm::CartesianMove>& targets) {
    constexpr double kLeadIn = 0.03;  // m
    const motion::JointVector q = arm_.chain_of(state_);
    if (first.kind != motion::SegmentKind::lin ||
        model_.kinematics->singularity(q, motion::kSingularStart) == motion::Singularity::none)
      return std::nullopt;
    const Eigen::Vector3d start = arm_.forward(q).position;
    const Eigen::Vector3d line = first.target.position - start;
    if (line.norm() < 2 * kLeadIn) return std::nullopt;
    motion::PathMove ptp;
    ptp.kind = motion::MoveKind::ptp;
    ptp.line = m.line;
    ptp.position = start + line.normalized() * kLeadIn;
    ptp.roll = m.roll;
    ptp.pitch = m.pitch;
    ptp.yaw = m.yaw;
    const std::vector<double> before = state_;
    using motion::Elbow;
    for (Elbow elbow : {Elbow::up, Elbow::down, Elbow::left, Elbow::right}) {
      ptp.elbow = elbow;
      try {
        plan_ptp(ptp);
      } catch (const ArmctlError&) {
        continue;  // no solution with this elbow (or not this arm's kind of elbow)
      }
      auto plan = arm::plan_path(model_, state_, arm::path_segments(arm_, state_, targets));
      if (plan) {
        pieces_.back().label = fmt::format("{}: joint move off the singular start, {:.0f} mm along the line",
                                           where(m), kLeadIn * 1e3);
        return std::move(plan).value();
      }
      pieces_.pop_back();
      state_ = before;
    }
    return std::nullopt;
  }

  arm::Arm& arm_;
  const arm::ArmModel& model_;
  std::vector<double> state_;
  std::vector<Piece> pieces_;
};

// The largest distance of the tool point, as read back during the motion, from where the
// plan had it at that instant (mm).
double tool_following_error(const arm::Arm& arm, const arm::MotionReport& r) {
  double worst = 0;
  for (const auto& s : r.reads_log) {
    const motion::Pose planned = arm.forward(arm.chain_of(s.planned));
    const motion::Pose measured = arm.forward(arm.chain_of(s.measured));
    worst = std::max(worst, (planned.position - measured.position).norm());
  }
  return worst * 1e3;
}

// The largest distance of the tool point, as read back during the motion, from the path
// itself (mm): the path sampled every 0.5 mm of its length.
double tool_path_error(const arm::Arm& arm, const arm::MotionReport& r, const motion::CartesianPath& path) {
  std::vector<Eigen::Vector3d> points;
  double length = 0;
  for (const auto& seg : path.segments()) length += seg.length;
  const int n = std::max(2, static_cast<int>(length / 0.0005));
  for (int k = 0; k <= n; ++k) points.push_back(path.at(path.duration() * k / n).position);
  double worst = 0;
  for (const auto& s : r.reads_log) {
    const Eigen::Vector3d p = arm.forward(arm.chain_of(s.measured)).position;
    double nearest = 1e9;
    for (const auto& q : points) nearest = std::min(nearest, (q - p).norm());
    worst = std::max(worst, nearest);
  }
  return worst * 1e3;
}

}  // namespace

void run_path_moves(session::ArmSession& session, const std::vector<motion::PathMove>& moves, const MotionCliOptions& options) {
  arm::Arm& arm = *session.arm;
  auto here = arm.read();
  if (!here) throw ArmctlError(here.error());
  std::vector<Piece> pieces = Planner(arm, here->positions).plan(moves);  // every check first

  double total = 0;
  for (const auto& p : pieces) total += p.motion.duration;
  if (options.json)
    print_json_line(json{{"event", "planned"}, {"moves", moves.size()}, {"pieces", pieces.size()},
                            {"duration_s", total / options.speed_override}});
  else
    fmt::print("planned {} move{} ({} piece{}), {:.1f} s\n", moves.size(), moves.size() == 1 ? "" : "s",
               pieces.size(), pieces.size() == 1 ? "" : "s", total / options.speed_override);
  std::fflush(stdout);

  Interrupted interrupted;
  StopOnSignals on_signals(interrupted);
  const bool progress_line = !options.json && isatty(STDERR_FILENO);
  double done_before = 0;
  for (const Piece& piece : pieces) {
    arm::ExecutorOptions eo;
    eo.speed_override = options.speed_override;
    eo.command = [&](const arm::MotionProgress&) {
      return interrupted ? arm::MotionCommand::stop : arm::MotionCommand::none;
    };
    Duration last_shown{};
    eo.on_point = [&](const arm::MotionProgress& p) {
      if (total < 1.0 || p.elapsed - last_shown < std::chrono::milliseconds(250)) return;
      last_shown = p.elapsed;
      const double left = (total - done_before - p.t) / options.speed_override;
      if (options.json)
        print_json_line(json{{"event", "progress"}, {"line", piece.line}, {"t", done_before + p.t},
                                {"left_s", left}});
      else if (progress_line)
        fmt::print(stderr, "\r{}: {:3.0f} %, {:.1f} s left   ", piece.label, 100 * (done_before + p.t) / total, left);
    };
    auto report = arm::execute_motion(arm, piece.motion, eo);
    if (progress_line) fmt::print(stderr, "\r\033[K");
    if (!report) throw ArmctlError(ErrorKind(report.error().kind), fmt::format("{}: {}", piece.label, report.error().message));
    if (options.trace) options.trace->add(arm, piece.line, piece.motion, *report);
    const double following_mm = tool_following_error(arm, *report);
    // Cartesian pieces only (a plain double: g++ 12 at -O2 warns on an optional here).
    const double path_mm = piece.path ? tool_path_error(arm, *report, *piece.path) : 0.0;
    if (options.json) {
      json event{{"event", report->completed ? "done" : "stopped"},
                 {"line", piece.line},
                 {"elapsed_s", std::chrono::duration<double>(report->elapsed).count()},
                 {"points", report->points},
                 {"reads", report->reads},
                 {"period_ms", std::chrono::duration<double, std::milli>(report->period).count()},
                 {"following_error_mm", following_mm}};
      event["held_s"] = std::chrono::duration<double>(report->held).count();
      if (piece.path) event["path_error_mm"] = path_mm;
      print_json_line(event);
    } else {
      // A host late beyond the points' lead held the motion (docs/motion.md): say so when it
      // was more than a period, so a slow run on a busy machine explains itself.
      const std::string held = report->held > report->period
                                   ? fmt::format("; held {:.2f} s for a late host",
                                                 std::chrono::duration<double>(report->held).count())
                                   : std::string();
      fmt::print("{}: {} in {:.2f} s, {} points every {:.1f} ms; read back {} times: tool within {:.2f} mm of the "
                 "plan{}{}\n",
                 piece.label, report->completed ? "done" : "stopped",
                 std::chrono::duration<double>(report->elapsed).count(), report->points,
                 std::chrono::duration<double, std::milli>(report->period).count(), report->reads, following_mm,
                 piece.path ? fmt::format(", {:.2f} mm of the path", path_mm) : std::string(), held);
    }
    std::fflush(stdout);
    if (!report->completed)
      throw ArmctlError(ErrorKind::device, fmt::format("stopped by a signal at {} (the arm is at rest on the path)",
                                                       piece.label));
    done_before += piece.motion.duration;
  }
  // The last point is due when the motion ends: let the arm get there before reporting.
  if (auto s = arm.wait(); !s) throw ArmctlError(s.error());
}

}  // namespace armctl::cli
