#include "arm/run_motion.hpp"

#include <algorithm>

#include "core/quantity.hpp"
#include "motion/move_limits.hpp"

namespace armctl::arm {

namespace {

bool stopping(MotionCommand c) { return c == MotionCommand::stop || c == MotionCommand::abort; }

class Runner {
 public:
  Runner(Arm& arm, const Plan& plan, const RunHooks& hooks) : arm_(arm), plan_(plan), hooks_(hooks) {}

  Result<RunReport> run() {
    const TimePoint began = arm_.clock().now();
    for (const PlannedPiece& piece : plan_.pieces) {
      if (stop_asked()) {
        report_.stopped = true;
        return finish(began);
      }
      Status s = Ok{};
      bool ended = true;  // ran to its end
      switch (piece.kind) {
        case PieceKind::message:
          event(RunEventKind::message, piece);
          break;
        case PieceKind::wait:
          event(RunEventKind::piece_started, piece);
          ended = idle(piece.seconds, s);
          if (ended && s) done_ += piece.seconds;
          break;
        case PieceKind::board_move:
          if (hooks_.before_piece && !hooks_.before_piece(piece)) return finish(began);
          event(RunEventKind::piece_started, piece);
          ended = board_move(piece, s);
          break;
        case PieceKind::motion:
          if (hooks_.before_piece && !hooks_.before_piece(piece)) return finish(began);
          event(RunEventKind::piece_started, piece);
          ended = stream(piece, s);
          break;
      }
      if (!s) return hooks_.label_errors ? s.error().prefixed(piece.label + ": ") : s.error();
      if (!ended) {
        report_.stopped = true;
        return finish(began);
      }
      if (piece.kind != PieceKind::message) event(RunEventKind::piece_done, piece, last_report_);
      last_report_ = nullptr;
      ++report_.pieces;
    }
    report_.completed = report_.pieces == plan_.pieces.size();
    if (report_.completed && hooks_.wait_for_arrival && last_streamed_) {
      // The last point is due when the motion ends: let the arm get there.
      auto arrived = arm_.wait(hooks_.wait);
      if (!arrived) {
        if (!stop_asked()) return not_arrived(arrived.error());
        report_.stopped = true;
        report_.completed = false;
      } else {
        report_.arrived = *arrived;
      }
    }
    return finish(began);
  }

 private:
  // A stall is not a late arrival: it keeps its own detail for the app to map.
  Error not_arrived(const Error& e) const { return hooks_.not_arrived && !stall_of(e) ? hooks_.not_arrived(e) : e; }

  // A contact the executor's look-ahead found names the piece's moves, as a refusal does.
  static Error with_piece(Error e, const PlannedPiece& piece) {
    if (auto* d = std::any_cast<CollisionDetail>(&e.detail)) {
      d->first_move = piece.first_move;
      d->last_move = piece.last_move;
      d->line = piece.first_line;
    }
    return e;
  }

  MotionCommand command() const { return hooks_.command ? hooks_.command() : MotionCommand::none; }
  bool stop_asked() const { return stopping(command()); }

  double left_after(double nominal_done) const {
    double left = 0, seen = 0;
    for (const auto& p : plan_.pieces) {
      const double d = p.duration();
      const double rest = std::clamp(seen + d - nominal_done, 0.0, d);
      left += p.kind == PieceKind::motion ? rest / hooks_.speed_override : rest;
      seen += d;
    }
    return left;
  }

  void event(RunEventKind kind, const PlannedPiece& piece, const MotionReport* report = nullptr, double within = 0) {
    if (hooks_.on_event) hooks_.on_event({kind, &piece, done_ + within, left_after(done_ + within), report});
  }

  Result<RunReport> finish(TimePoint began) {
    report_.elapsed = arm_.clock().now() - began;
    report_.t_reached = done_;
    return report_;
  }

  // Idles `seconds` on the device's clock in slices, asking for a stop between them. False:
  // stopped.
  bool idle(double seconds, Status& status) {
    const Duration total = std::chrono::duration_cast<Duration>(std::chrono::duration<double>(seconds));
    Duration waited{};
    while (waited < total) {
      if (command() != MotionCommand::none) return false;
      const Duration slice = std::min<Duration>(total - waited, std::chrono::milliseconds(20));
      if (auto ok = arm_.device().idle(slice); !ok) {
        status = ok.error();
        return true;
      }
      waited += slice;
    }
    return true;
  }

  // Sends the move; the device interpolates over its duration; then waits for arrival
  // (within its duration plus the wait's timeout). A stop meanwhile halts the arm.
  bool board_move(const PlannedPiece& piece, Status& status) {
    const Duration duration = std::chrono::duration_cast<Duration>(std::chrono::duration<double>(piece.seconds));
    if (auto sent = arm_.send(piece.targets, duration); !sent) {
      status = sent.error();
      return true;
    }
    last_streamed_ = false;
    if (!hooks_.wait_for_arrival) {
      done_ += piece.seconds;
      return true;
    }
    WaitOptions w = hooks_.wait;
    w.timeout += duration;
    auto user_interrupt = w.interrupted;
    w.interrupted = [&] { return stop_asked() || (user_interrupt && user_interrupt()); };
    auto arrived = arm_.wait(w);
    if (!arrived) {
      if (stop_asked()) {
        (void)arm_.stop();  // halted where it is
        return false;
      }
      status = not_arrived(arrived.error());
      return true;
    }
    report_.arrived = *arrived;
    done_ += piece.seconds;
    return true;
  }

  bool stream(const PlannedPiece& piece, Status& status) {
    ExecutorOptions eo = hooks_.executor;
    eo.speed_override = hooks_.speed_override;
    eo.command = [&](const MotionProgress& p) {
      const MotionCommand c = command();
      return c == MotionCommand::none && hooks_.executor.command ? hooks_.executor.command(p) : c;
    };
    Duration last_shown{};
    eo.on_point = [&](const MotionProgress& p) {
      if (hooks_.executor.on_point) hooks_.executor.on_point(p);
      if (p.elapsed - last_shown < hooks_.progress_every) return;
      last_shown = p.elapsed;
      event(RunEventKind::progress, piece, nullptr, p.t);
    };
    auto r = execute_motion(arm_, piece.motion, eo);
    if (!r) {
      status = with_piece(r.error(), piece);
      return true;
    }
    motion_report_ = *r;
    report_.last_motion = *r;
    last_report_ = &motion_report_;
    last_streamed_ = true;
    if (r->largest_following_error > report_.largest_following_error) {
      report_.largest_following_error = r->largest_following_error;
      report_.largest_following_joint = r->largest_following_joint;
    }
    done_ += r->t_reached;
    if (!r->completed) {
      event(RunEventKind::piece_done, piece, last_report_);
      return false;
    }
    return true;
  }

  Arm& arm_;
  const Plan& plan_;
  const RunHooks& hooks_;
  RunReport report_;
  MotionReport motion_report_;
  const MotionReport* last_report_ = nullptr;
  bool last_streamed_ = false;
  double done_ = 0;
};

}  // namespace

Result<RunReport> run_motion(Arm& arm, const Plan& plan, const RunHooks& hooks) {
  if (auto ok = check_fraction_in(hooks.speed_override, "speed override", motion::kMinSpeedFraction,
                                  motion::kMaxSpeedFraction);
      !ok)
    return ok.error();
  if (plan.start.size() != std::size_t(arm.model().joint_count()))
    return Error{ErrorKind::invalid_argument, "the plan is not for this arm (its start has another joint count)"};
  return Runner(arm, plan, hooks).run();
}

}  // namespace armctl::arm
