#include "arm/motion_executor.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "arm/arm_kinematics.hpp"
#include "core/quantity.hpp"
#include "motion/move_limits.hpp"
#include "scene/motion_check.hpp"

namespace armctl::arm {

namespace {

double seconds(Duration d) { return std::chrono::duration<double>(d).count(); }

// Quintic "smootherstep": rate and its first two derivatives continuous at both ends, so a
// pause or a stop adds no jerk step. Peak slope 15/8.
constexpr double kRampPeakSlope = 1.875;
double smootherstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * x * (x * (x * 6 - 15) + 10);
}

class RateRamp {
 public:
  explicit RateRamp(double rate) : from_(rate), to_(rate) {}
  void start(TimePoint at, double from, double to, double length_s) {
    at_ = at;
    from_ = from;
    to_ = to;
    length_ = std::max(length_s, 1e-9);
    active_ = true;
  }
  // The rate at `now`; the ramp ends once `now` is past it.
  double at(TimePoint now) {
    const double r = value(now);
    if (active_ && seconds(now - at_) >= length_) active_ = false;
    return r;
  }
  double value(TimePoint t) const {
    if (!active_) return to_;
    return from_ + (to_ - from_) * smootherstep(seconds(t - at_) / length_);
  }
  bool active() const { return active_; }
  double goal() const { return to_; }

 private:
  TimePoint at_{};
  double from_ = 0, to_ = 0, length_ = 1;
  bool active_ = false;
};

}  // namespace

// The maps are affine, so the difference of two points is the linear part.
void to_device(const ArmModel& model, Protocol p, const std::vector<double>& q, const std::vector<double>& v,
               std::vector<double>& dq, std::vector<double>& dv) {
  dq = model.to_device(p, q);
  std::vector<double> ahead(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) ahead[i] = q[i] + v[i];
  dv = model.to_device(p, ahead);
  for (std::size_t i = 0; i < dv.size(); ++i) dv[i] -= dq[i];
}

double following_threshold(const ArmModel& model, std::size_t joint, const ExecutorOptions& o) {
  if (joint < o.following_error.size() && o.following_error[joint] > 0) return o.following_error[joint];
  return model.joints[joint].dimension == Dimension::length ? o.following_error_length : o.following_error_angle;
}

Status check_following(const ArmModel& model, const std::vector<double>& measured, const std::vector<double>& planned,
                       const ExecutorOptions& options, std::string_view what, double t, double& largest,
                       int& largest_joint) {
  for (std::size_t i = 0; i < planned.size() && i < measured.size(); ++i) {
    // A gripper that closes on a part stops short of its plan by design (and a bus servo
    // gripper starts late when the host is slow): only the arm's joints follow the plan.
    if (model.gripper && model.gripper->joint == int(i)) continue;
    const double err = std::abs(measured[i] - planned[i]);
    if (err > largest) {
      largest = err;
      largest_joint = int(i);
    }
    if (const double limit = following_threshold(model, i, options); err > limit)
      return Error{ErrorKind::device,
                   fmt::format("{}: following error on joint {}: it is at {} but should be at {} ({} behind the "
                               "plan, the limit is {}); the arm was halted",
                               what, model.joints[i].name, format_joint_value(model, int(i), measured[i]),
                               format_joint_value(model, int(i), planned[i]), format_joint_value(model, int(i), err),
                               format_joint_value(model, int(i), limit)),
                   FollowingError{int(i), model.joints[i].name, measured[i], planned[i], limit, t}};
  }
  return Ok{};
}

double rate_ramp_seconds(const std::vector<double>& nominal_velocity, const std::vector<double>& accel_budget,
                         double rate_change) {
  double worst = 0;  // s^2 of nominal velocity per unit of budget
  for (std::size_t i = 0; i < nominal_velocity.size() && i < accel_budget.size(); ++i)
    if (accel_budget[i] > 0) worst = std::max(worst, std::abs(nominal_velocity[i]) / accel_budget[i]);
  return kRampPeakSlope * std::abs(rate_change) * worst;
}

namespace {

class Execution {
 public:
  Execution(Arm& arm, const PlannedMotion& motion, const ExecutorOptions& options)
      : arm_(arm), motion_(motion), options_(options), model_(arm.model()), device_(arm.device()),
        clock_(arm.clock()), stall_(arm.stall_watch(options.stall_time)) {
    const std::size_t n = std::size_t(model_.joint_count());
    pos_.resize(n);
    vel_.resize(n);
    acc_.resize(n);
  }

  Result<MotionReport> run() {
    // Every app's override (the CLI's --override, OVERRIDE in programs, Python's
    // speed_override, the HTTP API's speed) within one range.
    if (auto ok = check_fraction_in(options_.speed_override, "speed override", motion::kMinSpeedFraction,
                                    motion::kMaxSpeedFraction);
        !ok)
      return ok.error();
    const double top = options_.speed_override;
    if (!motion_.sample || !(motion_.duration >= 0) || !std::isfinite(motion_.duration))
      return Error{ErrorKind::invalid_argument, "the motion has no samples or no finite duration"};
    if (auto at_start = check_start(); !at_start) return at_start.error();

    period_ = options_.period.value_or(device_.stream_period(false));
    if (period_ <= Duration{0}) period_ = std::chrono::milliseconds(1);
    read_time_ = device_.stream_period(true) - device_.stream_period(false);
    // Reads take the link from the stream: at most one in four slots by default.
    const Duration read_every = options_.read_interval.value_or(std::max(device_.poll_interval(), 4 * period_));
    latency_ = device_.stream_latency();
    report_.period = period_;

    const TimePoint start = clock_.now();
    TimePoint last = start, next_read = start + read_every;
    double rate = top;
    bool paused = false, stopping = false;
    RateRamp ramp(top);

    for (;;) {
      const TimePoint now = clock_.now();
      const double new_rate = ramp.at(now);
      const double mean_rate = 0.5 * (rate + new_rate);
      double advance = mean_rate * seconds(now - last);
      // Each point leads by the latency plus its interval. A step that overran that by more
      // than one more step (the host was not scheduled, a read hung) found the arm at rest
      // at the last point: nominal time goes no further than that point, so the motion goes
      // on from where the arm is instead of jumping to where the plan went meanwhile (a jump
      // no servo can follow, and a following-error halt). Shorter overruns are the loop's
      // own jitter (a slow link's step is not exactly its interval) and are let through.
      const double overrun_allowed = mean_rate * seconds(period_ + read_time_);
      if (report_.points > 0 && last_due_ < motion_.duration && t_ + advance > last_due_ + overrun_allowed) {
        ++report_.late_steps;
        report_.held += std::chrono::duration_cast<Duration>(
            std::chrono::duration<double>((t_ + advance - last_due_) / mean_rate));
        advance = std::max(0.0, last_due_ - t_);
      }
      t_ += advance;
      rate = new_rate;
      last = now;
      t_ = std::min(t_, motion_.duration);
      MotionProgress progress{now - start, t_, motion_.duration, rate, paused, report_.points};

      if (t_ >= motion_.duration) return finish(start, true, false);
      if (stopping && !ramp.active() && rate <= 0) {
        // At rest on the path: the last point sent led a little; this one is where it stopped.
        motion_.sample(t_, pos_, vel_, acc_);
        std::fill(vel_.begin(), vel_.end(), 0.0);
        std::vector<double> dq, dv;
        to_device(model_, device_.protocol(), pos_, vel_, dq, dv);
        if (auto s = device_.stream(dq, dv, period_); !s) return halted(s.error());
        ++report_.points;
        auto done = finish(start, false, true);
        if (contact_ahead_) return collision_ahead(false);
        return done;
      }

      // A contact ahead (the scene changed since the plan): stop on the path before it, or
      // at once where a ramp down would not end short of it.
      if (!stopping && options_.look_ahead > Duration{0}) {
        if (auto c = look_ahead(rate)) {
          contact_ahead_ = std::move(c);
          const double length = ramp_seconds(rate, 0);
          const double rest = t_ + 0.5 * rate * length + rate * seconds(latency_ + period_ + read_time_);
          if (rest >= contact_ahead_->fraction * motion_.duration) {
            if (auto s = device_.stop(); !s) return s.error();
            (void)finish(start, false, true);  // where it was halted: the error says the rest
            return collision_ahead(true);
          }
          ramp.start(now, rate, 0, length);
          stopping = true;
          paused = false;
        }
      }

      const MotionCommand cmd = options_.command ? options_.command(progress) : MotionCommand::none;
      if (cmd == MotionCommand::abort) {
        if (auto s = device_.stop(); !s) return s.error();
        return finish(start, false, true);
      }
      if ((cmd == MotionCommand::pause || cmd == MotionCommand::stop) && !stopping && (ramp.goal() > 0)) {
        ramp.start(now, rate, 0, ramp_seconds(rate, 0));
        paused = cmd == MotionCommand::pause;
        stopping = cmd == MotionCommand::stop;
      } else if (cmd == MotionCommand::stop && paused) {
        paused = false;
        stopping = true;
      } else if (cmd == MotionCommand::resume && paused) {
        ramp.start(now, rate, top, ramp_seconds(rate, top));
        paused = false;
      }

      const bool read_now = now >= next_read;
      if (rate > 0 || ramp.active()) {
        const Duration in = period_ + (read_now ? read_time_ : Duration{0});
        // Where nominal time will be when the device gets there (the ramp's rate then, too).
        const double ahead = 0.5 * (rate + ramp.value(now + latency_ + in)) * seconds(latency_ + in);
        const double due = std::min(motion_.duration, t_ + ahead);
        last_due_ = due;
        motion_.sample(due, pos_, vel_, acc_);
        for (double& v : vel_) v *= rate;
        std::vector<double> dq, dv;
        to_device(model_, device_.protocol(), pos_, vel_, dq, dv);
        if (auto s = device_.stream(dq, dv, in); !s) return halted(s.error());
        ++report_.points;
      }
      if (read_now) {
        // (A stall has stopped the arm and released the joint: a halt would hold it again.)
        if (auto f = read_back(start, t_, rate); !f) return stall_of(f.error()) ? f.error() : halted(f.error());
        next_read = clock_.now() + read_every;
      }
      if (options_.on_point) options_.on_point(MotionProgress{clock_.now() - start, t_, motion_.duration, rate,
                                                                paused, report_.points});
      const TimePoint due_next = now + period_ + (read_now ? read_time_ : Duration{0});
      if (due_next > clock_.now())
        if (auto s = device_.idle(due_next - clock_.now()); !s) return halted(s.error());
    }
  }

 private:
  Status check_start() {
    auto now = arm_.read();
    if (!now) return now.error();
    motion_.sample(0, pos_, vel_, acc_);
    for (std::size_t i = 0; i < pos_.size(); ++i)
      if (std::abs(now->positions[i] - pos_[i]) > following_threshold(model_, i, options_))
        return Error{ErrorKind::invalid_argument,
                     fmt::format("{}: joint {} is at {}, but the motion starts at {}: plan it from where the arm "
                                 "stands", motion_.what, model_.joints[i].name,
                                 format_joint_value(model_, int(i), now->positions[i]),
                                 format_joint_value(model_, int(i), pos_[i]))};
    return Ok{};
  }

  // The ramp length from `from` to `to` that keeps every joint's extra acceleration
  // (|dq/dt_nominal| |dr/dt|) within what its limit leaves over the motion's own
  // acceleration in the stretch the ramp covers (at least a quarter of the limit).
  double ramp_seconds(double from, double to) {
    std::vector<double> peak_v(pos_.size(), 0.0), peak_a(pos_.size(), 0.0), budget(pos_.size());
    double length = 2 * seconds(period_);
    for (int pass = 0; pass < 3; ++pass) {
      const double span = 0.5 * (from + to) * length + 1e-3;
      for (int k = 0; k <= 16; ++k) {
        motion_.sample(std::min(motion_.duration, t_ + span * k / 16.0), pos_, vel_, acc_);
        for (std::size_t i = 0; i < pos_.size(); ++i) {
          peak_v[i] = std::max(peak_v[i], std::abs(vel_[i]));
          peak_a[i] = std::max(peak_a[i], std::abs(acc_[i]));
        }
      }
      const double r2 = std::max(from, to) * std::max(from, to);
      for (std::size_t i = 0; i < pos_.size(); ++i) {
        const double limit = model_.joints[i].limits.acceleration;
        budget[i] = std::max(0.25 * limit, limit - peak_a[i] * r2);
      }
      length = std::max(length, rate_ramp_seconds(peak_v, budget, to - from));
    }
    return length;
  }

  Status read_back(TimePoint start, double t_now, double rate) {
    const TimePoint before = clock_.now();
    auto s = arm_.read();
    if (!s) return s.error();
    ++report_.reads;
    if (options_.on_read) options_.on_read(*s);
    // The device answers about halfway through the exchange, and it cannot be past the last
    // point it was sent (a read that hung for a while finds it resting there).
    const double t_read =
        std::min({motion_.duration, last_due_, t_now + rate * 0.5 * seconds(clock_.now() - before)});
    motion_.sample(t_read, pos_, vel_, acc_);
    report_.reads_log.push_back({clock_.now() - start, pos_, s->positions});
    if (auto f = check_following(model_, s->positions, pos_, options_, motion_.what, t_read,
                                 report_.largest_following_error, report_.largest_following_joint);
        !f)
      return f;
    planned_.assign(pos_.begin(), pos_.end());
    if (auto stall = stall_.read(s->time, s->positions, planned_)) return arm_.stalled(std::move(*stall), motion_.what);
    return Ok{};
  }

  // The stretch from where the look-ahead last reached to the next `look_ahead` of device
  // time at `rate`, plus a stop's length and the points' lead, against the collision world
  // as it is now; a new world (set_scene) is checked again from where the arm is. Checked in
  // chunks of twice what is needed, so that not every point asks. The contact found, with
  // `fraction` of the motion where it is.
  std::optional<CollisionDetail> look_ahead(double rate) {
    const auto kinematics = arm_.kinematics();
    const auto& world = kinematics->collisions();
    if (!world) return std::nullopt;
    if (world != world_) {
      world_ = world;
      checked_to_ = t_;
    }
    if (checked_to_ >= motion_.duration) return std::nullopt;
    const double lead = rate * seconds(options_.look_ahead + latency_ + period_ + read_time_);
    if (checked_to_ >= t_ + lead + stop_span_) return std::nullopt;
    stop_span_ = 0.5 * rate * ramp_seconds(rate, 0);
    const double from = checked_to_;
    const double to = std::min(motion_.duration, t_ + 2 * (lead + stop_span_) + 1e-3);
    std::vector<double> v(pos_.size()), a(pos_.size());
    const scene::MotionCheck check = scene::check_motion(*world, to - from, [&](double t, std::vector<double>& q) {
      q.resize(pos_.size());
      motion_.sample(from + t, q, v, a);
    });
    checked_to_ = to;
    if (!check.contact) return std::nullopt;
    CollisionDetail d;
    d.contact = *check.contact;
    d.fraction = motion_.duration > 0 ? (from + check.at) / motion_.duration : 0;
    d.joints = check.joints;
    d.tool_point = kinematics->pose_at(check.joints).position;
    d.while_moving = true;
    return d;
  }

  Error collision_ahead(bool halted_at_once) {
    CollisionDetail d = std::move(*contact_ahead_);
    d.stopped_at = motion_.duration > 0 ? t_ / motion_.duration : 0;
    // A limit (the fence, reduced mode's joint ranges) switched on while it moved, or a collision.
    const bool limit = d.contact.limit != scene::Limit::none;
    const std::string message = fmt::format(
        "{}: stopped before {} ({}): {:.0f}% into the motion, tool point at ({:.1f}, {:.1f}, {:.1f}) mm, {} "
        "{} {} (the {} changed after the motion was planned); the arm {} at {:.0f}%",
        motion_.what, limit ? fmt::format("leaving the {}", scene::to_string(d.contact.limit)) : "a collision",
        halted_at_once ? "too near to slow down on the path" : "found ahead while moving", 100 * d.fraction,
        d.tool_point.x() * 1e3, d.tool_point.y() * 1e3, d.tool_point.z() * 1e3, d.contact.first,
        limit ? "beyond" : "with", d.contact.second, limit ? "limits" : "scene",
        halted_at_once ? "was halted" : "is at rest on the path", 100 * d.stopped_at);
    return Error{ErrorKind::invalid_argument, message, std::move(d)};
  }

  Error halted(const Error& e) {
    (void)device_.stop();  // best effort: the error is what the caller needs
    return e;
  }

  Result<MotionReport> finish(TimePoint start, bool completed, bool stopped) {
    // Where the last point sent leads (for a stop: where the ramp came to rest).
    motion_.sample(std::min(motion_.duration, t_), pos_, vel_, acc_);
    arm_.expect_at(pos_);
    report_.elapsed = clock_.now() - start;
    report_.t_reached = t_;
    report_.completed = completed;
    report_.stopped = stopped;
    return report_;
  }

  Arm& arm_;
  const PlannedMotion& motion_;
  const ExecutorOptions& options_;
  const ArmModel& model_;
  ArmDevice& device_;
  const Clock& clock_;
  StallWatch stall_;
  std::vector<double> pos_, vel_, acc_;
  std::vector<std::optional<double>> planned_;  // where the plan has every joint at a read
  double t_ = 0;
  double last_due_ = 0;  // nominal time of the last point sent
  // The look-ahead: the world it checked against, how far (nominal s), the nominal length
  // of a stop at the last check's rate, and a contact found ahead.
  std::shared_ptr<const scene::CollisionWorld> world_;
  double checked_to_ = 0;
  double stop_span_ = 0;
  std::optional<CollisionDetail> contact_ahead_;
  Duration period_{}, read_time_{}, latency_{};
  MotionReport report_;
};

}  // namespace

Result<MotionReport> execute_motion(Arm& arm, const PlannedMotion& motion, const ExecutorOptions& options) {
  return Execution(arm, motion, options).run();
}

}  // namespace armctl::arm
