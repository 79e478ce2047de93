#include "program/program_runner.hpp"

#include <algorithm>

#include <fmt/core.h>

#include "core/quantity.hpp"
#include "motion/move_limits.hpp"

namespace armctl::program {

Result<RunReport> run_plan(arm::Arm& arm, const ProgramPlan& plan, const RunOptions& options) {
  if (auto ok = check_fraction_in(options.speed_override, "speed override", motion::kMinSpeedFraction,
                                  motion::kMaxSpeedFraction);
      !ok)
    return ok.error();
  RunReport report;
  const TimePoint began = arm.clock().now();
  auto command = [&] { return options.command ? options.command() : arm::MotionCommand::none; };
  auto event = [&](RunEvent e) {
    if (options.on_event) options.on_event(e);
  };
  double done = 0;
  auto left_after = [&](double nominal_done) {
    double left = 0, seen = 0;
    for (const auto& p : plan.pieces) {
      const double d = p.kind == PieceKind::motion ? p.motion.duration : p.seconds;
      const double rest = std::clamp(seen + d - nominal_done, 0.0, d);
      left += p.kind == PieceKind::motion ? rest / options.speed_override : rest;
      seen += d;
    }
    return left;
  };
  for (const PlannedPiece& piece : plan.pieces) {
    if (command() == arm::MotionCommand::stop || command() == arm::MotionCommand::abort) break;
    if (piece.kind == PieceKind::print) {
      event({RunEventKind::print, &piece, done, left_after(done), nullptr});
      ++report.pieces;
      continue;
    }
    if (piece.kind == PieceKind::wait) {
      event({RunEventKind::piece_started, &piece, done, left_after(done), nullptr});
      const Duration total = std::chrono::duration_cast<Duration>(std::chrono::duration<double>(piece.seconds));
      Duration waited{};
      bool stopped = false;
      while (waited < total) {
        if (command() != arm::MotionCommand::none) {
          stopped = true;
          break;
        }
        const Duration slice = std::min<Duration>(total - waited, std::chrono::milliseconds(20));
        if (auto ok = arm.device().idle(slice); !ok) return ok.error().prefixed(piece.label + ": ");
        waited += slice;
      }
      if (stopped) break;
      done += piece.seconds;
      event({RunEventKind::piece_done, &piece, done, left_after(done), nullptr});
      ++report.pieces;
      continue;
    }
    if (options.before_motion && !options.before_motion(piece)) break;
    event({RunEventKind::piece_started, &piece, done, left_after(done), nullptr});
    arm::ExecutorOptions eo = options.executor;
    eo.speed_override = options.speed_override;
    eo.command = [&](const arm::MotionProgress& p) {
      const arm::MotionCommand c = command();
      return c == arm::MotionCommand::none && options.executor.command ? options.executor.command(p) : c;
    };
    Duration last_shown{};
    eo.on_point = [&](const arm::MotionProgress& p) {
      if (options.executor.on_point) options.executor.on_point(p);
      if (p.elapsed - last_shown < std::chrono::milliseconds(250)) return;
      last_shown = p.elapsed;
      event({RunEventKind::progress, &piece, done + p.t, left_after(done + p.t), nullptr});
    };
    auto r = arm::execute_motion(arm, piece.motion, eo);
    if (!r) return r.error().prefixed(piece.label + ": ");
    report.largest_following_error = std::max(report.largest_following_error, r->largest_following_error);
    done += r->t_reached;
    event({RunEventKind::piece_done, &piece, done, left_after(done), &*r});
    if (!r->completed) break;
    ++report.pieces;
  }
  report.completed = report.pieces == plan.pieces.size();
  if (report.completed) {
    // The last point is due when the motion ends: let the arm get there.
    if (auto s = arm.wait(options.wait); !s) return s.error();
  }
  report.elapsed = arm.clock().now() - began;
  return report;
}

}  // namespace armctl::program
