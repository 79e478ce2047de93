#include "apps/armctl/clearance_words.hpp"
#include "apps/armctl/arm_motion.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "apps/armctl/arm_json.hpp"
#include "apps/armctl/json_output.hpp"
#include "apps/armctl/motion_trace.hpp"
#include "apps/armctl/serve_support.hpp"
#include "arm/plan_moves.hpp"
#include "arm/run_motion.hpp"
#include "core/quantity.hpp"

namespace armctl::cli {

namespace {

using nlohmann::json;

// Where a move came from, for messages: "line 12" of a path file, or the command line.
std::string where(const files::PathMove& m) {
  return m.line ? fmt::format("line {} ({})", m.line, files::to_string(m.kind)) : std::string("the move");
}

arm::CartesianGoal goal_of(const files::PathMove& m) {
  arm::CartesianGoal g;
  g.position = m.position;
  g.roll = m.roll;
  g.pitch = m.pitch;
  g.yaw = m.yaw;
  return g;
}

// A path file's move as the planner takes it.
arm::Move move_of(const arm::ArmModel& model, const files::PathMove& m) {
  arm::Move out{arm::WaitMove{}, where(m), m.line};
  if (m.kind == files::MoveKind::ptp) {
    arm::PtpMove ptp;
    if (!m.joints.empty()) {
      auto given = arm::joint_values_targets(model, m.joints);
      if (!given) throw ArmctlError(ErrorKind::invalid_argument, fmt::format("{}: {}", where(m), given.error().message));
      ptp.target = std::move(given).value();
    } else {
      arm::CartesianGoal goal = goal_of(m);
      goal.elbow = m.elbow;
      ptp.target = goal;
    }
    ptp.speed = m.speed_fraction;
    out.what = ptp;
    return out;
  }
  arm::CartesianMove t;
  t.kind = m.kind == files::MoveKind::circ ? motion::SegmentKind::circ : motion::SegmentKind::lin;
  t.goal = goal_of(m);
  t.via = m.via;
  t.speed = m.speed.value_or(motion::kDefaultToolSpeed);
  t.angular_speed = m.angular_speed.value_or(motion::kDefaultToolAngularSpeed);
  t.zone = m.zone;
  out.what = t;
  return out;
}

// Every move planned from where the arm stands (arm::plan_moves). A refusal names the move:
// "line 12 (PTP): why"; a run of LIN/CIRC its lines ("lines 3..5: segment 2 (LIN): why").
arm::Plan plan_path_moves(const arm::ArmKinematics& kinematics, const std::vector<double>& from,
                          const std::vector<files::PathMove>& path) {
  std::vector<arm::Move> moves;
  for (const auto& m : path) moves.push_back(move_of(kinematics.model(), m));
  arm::MoveRefusal refused;
  auto plan = arm::plan_moves(kinematics, from, moves, {}, &refused);
  if (plan) return std::move(plan).value();
  const Error& e = plan.error();
  const files::PathMove& first = path[refused.first_move];
  if (first.kind == files::MoveKind::ptp)
    throw ArmctlError(ErrorKind::invalid_argument, fmt::format("{}: {}", where(first), e.message));
  // The path's errors count segments from 1 within this run: say which lines.
  const std::string lines =
      first.line ? fmt::format("lines {}..{}: ", first.line, path[refused.last_move].line) : std::string();
  throw ArmctlError(e.prefixed(lines));
}

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

arm::JointState run_path_moves(session::ArmSession& session, const std::vector<files::PathMove>& moves, const MotionCliOptions& options) {
  std::string stopped_at;  // the piece running when a signal stops the run
  arm::Arm& arm = *session.arm;
  auto here = arm.read();
  if (!here) throw ArmctlError(here.error());
  const arm::Plan plan = plan_path_moves(*arm.kinematics(), here->positions, moves);  // every check first

  const double total = plan.duration;
  const std::size_t pieces = plan.pieces.size();
  Interrupted interrupted;
  StopOnSignals on_signals(interrupted);  // before the plan is said: a Ctrl-C after it stops the motion
  if (options.json) {
    json planned{{"event", "planned"}, {"moves", moves.size()}, {"pieces", pieces},
                 {"duration_s", total / options.speed_override}, {"targets", joint_values_json(arm.model(), plan.end())}};
    add_clearance_json(planned, plan.clearance);
    print_json_line(planned);
  } else {
    fmt::print("planned {} move{} ({} piece{}), {:.1f} s{}\n", moves.size(), moves.size() == 1 ? "" : "s", pieces,
               pieces == 1 ? "" : "s", total / options.speed_override,
               arm.scene().objects.empty() ? std::string() : "; " + clearance_words(plan.clearance));
  }
  std::fflush(stdout);

  const bool progress_line = !options.json && isatty(STDERR_FILENO);
  arm::RunHooks hooks;
  hooks.speed_override = options.speed_override;
  hooks.label_errors = true;
  hooks.command = [&] { return interrupted ? arm::MotionCommand::stop : arm::MotionCommand::none; };
  hooks.on_event = [&](const arm::RunEvent& e) {
    const arm::PlannedPiece& piece = *e.piece;
    if (e.kind == arm::RunEventKind::piece_started) stopped_at = piece.label;
    if (e.kind == arm::RunEventKind::progress) {
      if (total < 1.0) return;
      if (options.json)
        print_json_line(json{{"event", "progress"}, {"line", piece.first_line}, {"t", e.done}, {"left_s", e.left}});
      else if (progress_line)
        fmt::print(stderr, "\r{}: {:3.0f} %, {:.1f} s left   ", piece.label, 100 * e.done / total, e.left);
      return;
    }
    if (e.kind != arm::RunEventKind::piece_done || !e.report) return;
    const arm::MotionReport& report = *e.report;
    if (progress_line) fmt::print(stderr, "\r\033[K");
    if (options.trace) options.trace->add(arm, piece.first_line, piece.motion, report);
    const double following_mm = tool_following_error(arm, report);
    // Cartesian pieces only (a plain double: g++ 12 at -O2 warns on an optional here).
    const double path_mm = piece.path ? tool_path_error(arm, report, *piece.path) : 0.0;
    if (options.json) {
      json event{{"event", report.completed ? "done" : "stopped"},
                 {"line", piece.first_line},
                 {"elapsed_s", std::chrono::duration<double>(report.elapsed).count()},
                 {"points", report.points},
                 {"reads", report.reads},
                 {"period_ms", std::chrono::duration<double, std::milli>(report.period).count()},
                 {"following_error_mm", following_mm}};
      event["held_s"] = std::chrono::duration<double>(report.held).count();
      if (piece.path) event["path_error_mm"] = path_mm;
      print_json_line(event);
    } else {
      // A host late beyond the points' lead held the motion (docs/motion.md): say so when it
      // was more than a period, so a slow run on a busy machine explains itself.
      const std::string held = report.held > report.period
                                   ? fmt::format("; held {:.2f} s for a late host",
                                                 std::chrono::duration<double>(report.held).count())
                                   : std::string();
      fmt::print("{}: {} in {:.2f} s, {} points every {:.1f} ms; read back {} times: tool within {:.2f} mm of the "
                 "plan{}{}\n",
                 piece.label, report.completed ? "done" : "stopped",
                 std::chrono::duration<double>(report.elapsed).count(), report.points,
                 std::chrono::duration<double, std::milli>(report.period).count(), report.reads, following_mm,
                 piece.path ? fmt::format(", {:.2f} mm of the path", path_mm) : std::string(), held);
    }
    std::fflush(stdout);
  };
  auto report = arm::run_motion(arm, plan, hooks);
  if (progress_line) fmt::print(stderr, "\r\033[K");
  if (!report) throw ArmctlError(report.error());
  if (report->stopped)
    throw ArmctlError(ErrorKind::device,
                      fmt::format("stopped by a signal at {} (the arm is at rest on the path)", stopped_at));
  if (report->arrived) return *report->arrived;
  auto now = arm.read();
  if (!now) throw ArmctlError(now.error());
  return *now;
}

}  // namespace armctl::cli
