#include "devices/arm_controller/arm_controller.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/core.h>

#include "devices/joint_bus/bus_connection.hpp"

namespace armctl::arm_controller {

using joint_bus::JointMotionModel;
using joint_bus::JointProfile;
using joint_bus::MovingStart;
using joint_bus::PlanInput;
using joint_bus::PlannedJoint;
using joint_bus::as_quantized_by_joint;
using joint_bus::plan_synchronized_move;

namespace {

constexpr int kFaultLogEvery = 100;
// A joint off its plan without a fault is asked again this often.
constexpr Duration kFaultRecheck = std::chrono::milliseconds(250);  // a dead joint fails every sweep: log changes, then 1 in 100

}  // namespace

ArmController::ArmController(transport::JointBusLink& link, joint_bus::MasterOptions master_options,
                             ControllerConfig config, ControllerOptions options)
    : link_(link), master_(link, master_options), config_(std::move(config)), options_(std::move(options)) {
  if (config_.joints.empty())
    throw ArmctlError(ErrorKind::invalid_config, "arm config names no joints");
  for (const auto& jc : config_.joints) {
    if (jc.number > master_.joint_count())
      throw ArmctlError(ErrorKind::invalid_config,
                        fmt::format("arm config joint {} ({}) has no select line: the bus has joints 1..{}",
                                    int(jc.number), jc.name, master_.joint_count()));
    ids_.push_back(jc.number);
    Joint j;
    j.config = jc;
    j.profile = as_quantized_by_joint(JointProfile{jc.max_speed_cps, jc.max_accel_cps2});
    j.model = JointMotionModel(JointProfile{jc.max_speed_cps, jc.max_accel_cps2});
    joints_.push_back(std::move(j));
    JointSettings s;
    s.limits.servo = jc.number;
    settings_.joints[jc.number] = s;
  }
  settings_.info_joint = ids_.front();
  if (options_.state_dir) {
    std::error_code ec;
    std::filesystem::create_directories(*options_.state_dir, ec);
    if (ec)
      throw ArmctlError(ErrorKind::io, fmt::format("cannot create state dir {}: {}",
                                                   options_.state_dir->string(), ec.message()));
    auto loaded = load_settings(*options_.state_dir, settings_);
    if (!loaded) throw ArmctlError(loaded.error());
    settings_ = *loaded;
  }
  for (auto& j : joints_) j.offset = settings_.joints[j.config.number].saved_offset;
  const std::uint32_t baud = link_.baud();
  min_txn_ = wire_time(8, baud);
  txn_estimate_ = min_txn_ + wire_time(2, baud);
  now_ = clock().now();
}

ArmController::Joint& ArmController::at(int joint) {
  for (auto& j : joints_)
    if (j.config.number == joint) return j;
  throw ArmctlError(ErrorKind::invalid_argument, fmt::format("joint {} is not configured", joint));
}
const ArmController::Joint& ArmController::at(int joint) const {
  return const_cast<ArmController*>(this)->at(joint);
}

void ArmController::log(const std::string& line) const {
  if (options_.log) options_.log(line);
}

void ArmController::start() {
  for (auto& j : joints_) {
    timed([&] {
      auto r = master_.set_zone(j.config.number, j.config.zone_clicks);
      if (r) note_success(j);
      else note_fault(j, r.error(), "set_zone");
    });
  }
  for (std::size_t i = 0; i < joints_.size(); ++i) poll_next();
}

// ---------------------------------------------------------------- mapping

std::int32_t ArmController::target_clicks(ServoId servo, std::uint16_t position) const {
  const Joint& j = at(servo);
  return j.config.map.to_clicks(double(position) + j.offset);
}

rc_board::PositionRange ArmController::position_range(ServoId servo) const {
  const Joint& j = at(servo);
  const auto& limits = settings_.joints.at(servo).limits;
  // The map is monotonic, so the allowed positions are one interval: find its ends exactly.
  int lo = -1, hi = -1;
  for (int p = limits.position_min; p <= limits.position_max; ++p) {
    std::int32_t c = target_clicks(servo, static_cast<std::uint16_t>(p));
    if (c >= j.config.soft_min && c <= j.config.soft_max) {
      if (lo < 0) lo = p;
      hi = p;
    }
  }
  if (lo < 0) return rc_board::PositionRange{1, 0};  // nothing allowed (empty range)
  return rc_board::PositionRange{static_cast<std::uint16_t>(lo), static_cast<std::uint16_t>(hi)};
}

std::int16_t ArmController::position(ServoId servo) const {
  const Joint& j = at(servo);
  const std::int32_t clicks = j.status.clicks.value_or(0);
  return static_cast<std::int16_t>(std::clamp<std::int32_t>(j.config.map.to_rc(clicks), -32768, 32767));
}

// ---------------------------------------------------------------- scheduling

void ArmController::schedule(TimePoint due, int joint, OpKind kind, std::int16_t value) {
  Op op{due, next_seq_++, joint, kind, value};
  auto it = std::upper_bound(ops_.begin(), ops_.end(), op, [](const Op& a, const Op& b) {
    return a.due != b.due ? a.due < b.due : a.seq < b.seq;
  });
  ops_.insert(it, op);
}

void ArmController::cancel_ops(int joint) {
  std::erase_if(ops_, [&](const Op& op) { return op.joint == joint; });
}

std::optional<TimePoint> ArmController::next_due() const {
  if (ops_.empty()) return std::nullopt;
  return ops_.front().due;
}

void ArmController::advance_to(TimePoint now) { now_ = std::max(now_, now); }

void ArmController::anchor_model(Joint& j, TimePoint t) {
  // Nothing known about the setpoint (start-up, after a failed command): take the polled
  // position as at rest, as a move planned now will.
  if (!j.model.known() && j.status.loop_on) j.model.rest_at(j.status.clicks.value_or(0), t);
}

TimePoint ArmController::effect_instant() const {
  // Called right after a command's transaction: it took effect when its DATA word had
  // crossed the wire, before the two STATUS bytes.
  return clock().now() - wire_time(2, link_.baud());
}

Result<Duration> ArmController::move(std::span<const rc_board::ServoTarget> targets,
                                     Duration time, TimePoint now) {
  advance_to(now);
  for (const auto& t : targets) {
    const Joint& j = at(t.servo);
    if (!j.status.answering || !j.status.clicks) {
      // Refused whole: a synchronized move without one of its joints is not the move asked
      // for. The Board counts and logs the refusal.
      ++stats_.refused_moves;
      return Error{ErrorKind::device,
                   fmt::format("joint {} ({}) is not answering ({}); no joint moved", int(t.servo),
                               j.config.name,
                               j.status.last_fault.empty() ? "never read" : j.status.last_fault)};
    }
  }
  ++stats_.moves;
  const TimePoint bus_now = clock().now();
  const TimePoint start = now;
  const std::uint32_t baud = link_.baud();
  // drive_to takes effect once READY, COMMAND and DATA have crossed the wire.
  const Duration effect = wire_time(6, baud);

  std::vector<PlanInput> inputs;
  std::vector<std::int16_t> clicks;
  int loop_ons = 0;
  for (const auto& t : targets) {
    Joint& j = at(t.servo);
    cancel_ops(t.servo);  // what was not sent yet never happens: the model has only what was
    const std::int32_t c = target_clicks(t.servo, *t.position);  // the Board dropped "leave alone"
    clicks.push_back(static_cast<std::int16_t>(c));
    PlanInput in;
    in.joint = t.servo;
    in.profile = j.profile;
    in.zone = double(j.config.zone_clicks);
    in.target_q8 = c * 256;
    anchor_model(j, bus_now);
    if (j.status.loop_on && !j.model.settled_at(bus_now)) {
      // Still moving (or held short of its target): plan from the modelled setpoint.
      TimePoint tick{};
      MovingStart m{j.model.ramp_at(bus_now, &tick), j.model.target_q8(), tick - start};
      in.distance = std::abs(double(c) - m.ramp.setpoint_q8() / 256.0);
      in.moving = m;
      ++stats_.moving_starts;
    } else {
      const double from = j.status.loop_on ? j.model.setpoint_clicks_at(bus_now) : j.status.clicks.value_or(0);
      in.distance = std::abs(double(c) - from);
    }
    inputs.push_back(in);
    if (!j.status.loop_on) ++loop_ons;
  }
  // A joint at rest gets set_speed then drive_to back to back (a speed change on its own
  // would set an old target moving again); a moving one drive_to then set_speed (see
  // PlannedJoint); loop-on commands go first.
  const Duration lag = std::max(Duration::zero(), bus_now - start);
  const Duration setup = lag + txn_estimate_ * (loop_ons + 1) + effect;
  last_plan_ = plan_synchronized_move(inputs, time, setup, txn_estimate_ * 2);
  last_move_start_ = start;

  for (std::size_t i = 0; i < targets.size(); ++i) {
    const int n = targets[i].servo;
    Joint& j = at(n);
    const PlannedJoint& p = last_plan_.joints[i];
    if (!j.status.loop_on) schedule(bus_now, n, OpKind::loop_on, 1);
    const TimePoint drive_due = start + p.start - effect;
    if (p.drive_first) {
      schedule(drive_due, n, OpKind::drive_to, clicks[i]);
      // Streaming hosts often ask for the same speed again: save the bus the transaction.
      if (j.model.speed_percent() != p.percent)
        schedule(start + p.speed_at - effect, n, OpKind::speed, static_cast<std::int16_t>(p.percent));
    } else {
      schedule(drive_due - txn_estimate_, n, OpKind::speed, static_cast<std::int16_t>(p.percent));
      schedule(drive_due, n, OpKind::drive_to, clicks[i]);
    }
    if (p.switch_percent)
      schedule(start + p.switch_at - effect, n, OpKind::speed, static_cast<std::int16_t>(*p.switch_percent));
    j.status.loop_on = true;
    j.status.jogging = false;
    j.status.target = clicks[i];
    j.status.arrive_at = start + last_plan_.total;
  }
  return last_plan_.total;
}

void ArmController::torque_off(std::span<const ServoId> servos) {
  const TimePoint bus_now = clock().now();
  for (ServoId s : servos) {
    Joint& j = at(s);
    cancel_ops(s);
    schedule(bus_now, s, OpKind::loop_off, 0);
    j.model.forget();
    j.status.loop_on = false;
    j.status.jogging = false;
    j.status.target.reset();
  }
}

void ArmController::link_lost() {
  ops_.clear();
  for (auto& j : joints_) {
    j.model.forget();  // what the joint does now is unknown (a restarted arm starts afresh)
    j.status.target.reset();
    j.status.jogging = false;
    j.status.answering = false;
    j.status.last_fault = "joint bus link lost";
  }
}

void ArmController::halt(TimePoint now) {
  advance_to(now);
  ops_.clear();
  // 0 % brings each joint's setpoint to rest at its acceleration limit and holds it there.
  const TimePoint bus_now = clock().now();
  for (auto& j : joints_) {
    anchor_model(j, bus_now);
    schedule(bus_now, j.config.number, OpKind::speed, 0);
    j.status.jogging = false;
    j.status.target.reset();
  }
}

void ArmController::set_mode(ServoId servo, rc_board::ServoMode mode, std::int16_t speed,
                             TimePoint now) {
  advance_to(now);
  Joint& j = at(servo);
  const TimePoint bus_now = clock().now();
  if (mode == rc_board::ServoMode::servo) {
    if (j.status.jogging) {
      cancel_ops(servo);
      schedule(bus_now, servo, OpKind::speed, 0);
      j.status.jogging = false;
      j.status.target.reset();
    }
    return;
  }
  // Motor mode: a velocity jog toward the soft limit in the direction asked; the joint
  // stops there at the latest. Speed 1000 = the joint's top speed.
  cancel_ops(servo);
  anchor_model(j, bus_now);
  if (!j.status.loop_on) schedule(bus_now, servo, OpKind::loop_on, 1);
  j.status.loop_on = true;
  j.status.jogging = true;
  j.status.target.reset();
  const int percent = (std::abs(int(speed)) + 9) / 10;
  schedule(bus_now, servo, OpKind::speed, static_cast<std::int16_t>(percent));
  if (speed != 0) {
    const bool up = (speed > 0) == (j.config.map.clicks_per_unit() > 0);
    schedule(bus_now, servo, OpKind::drive_to, up ? j.config.soft_max : j.config.soft_min);
  }
}

// ---------------------------------------------------------------- settings

std::uint16_t ArmController::battery_millivolts() const {
  return options_.supply_millivolts ? options_.supply_millivolts() : config_.supply_millivolts;
}

void ArmController::adjust_offset(ServoId servo, std::int8_t offset) { at(servo).offset = offset; }

std::int8_t ArmController::offset(ServoId servo) const { return at(servo).offset; }

Status ArmController::save_offsets(std::span<const ServoId> servos) {
  ControllerSettings before = settings_;
  for (ServoId s : servos) settings_.joints[s].saved_offset = at(s).offset;
  if (!options_.state_dir) return Ok{};
  Status st = save_settings(*options_.state_dir, settings_);
  if (!st) settings_ = before;
  return st;
}

rc_board::BusServoInfoReply ArmController::bus_servo_info() const {
  const int n = settings_.info_joint;
  // temp 0: the joint controllers have no temperature sensor.
  return rc::bus_servo_info_reply(settings_.joints.at(n).limits, at(n).offset,
                                  position(static_cast<ServoId>(n)), 0, battery_millivolts());
}

Status ArmController::write_bus_servo_info(const rc_board::BusServoLimits& limits) {
  if (!config_.joint(limits.servo)) {  // joints cannot be renumbered from here
    return Error{ErrorKind::device,
                 fmt::format("joint {} is not configured on this arm controller", int(limits.servo))};
  }
  ControllerSettings before = settings_;
  settings_.joints[limits.servo].limits = limits;
  settings_.info_joint = limits.servo;
  if (options_.state_dir) {
    Status st = save_settings(*options_.state_dir, settings_);
    if (!st) {
      settings_ = before;
      return st;
    }
  }
  return Ok{};
}

// ---------------------------------------------------------------- bus work

void ArmController::timed(const std::function<void()>& transaction) {
  const TimePoint t0 = clock().now();
  const auto failures = master_.counters().failures;
  transaction();
  const Duration took = clock().now() - t0;
  if (master_.counters().failures == failures) {
    // Successful transactions teach how long one takes on this link (a slow one counts
    // fully: better a plan that starts a joint early than one that keeps it waiting).
    txn_estimate_ = std::max(min_txn_, took > txn_estimate_ ? took : (txn_estimate_ * 7 + took) / 8);
  }
}

void ArmController::note_success(Joint& j) {
  if (!j.status.answering && j.status.faults > 0)
    log(fmt::format("joint {} ({}) answers again", int(j.config.number), j.config.name));
  j.status.answering = true;
}

void ArmController::note_fault(Joint& j, const Error& f, const char* doing) {
  ++j.status.faults;
  const joint_bus::JointFailure* failure = joint_bus::joint_failure(f);
  const auto now = failure ? std::optional(std::pair(failure->kind, failure->stage)) : std::nullopt;
  const bool changed = j.status.answering || j.last_failure != now || j.status.faults == 1;
  j.last_failure = now;
  j.status.answering = false;
  j.status.last_fault = f.message;
  if (changed || j.status.faults % kFaultLogEvery == 0)
    log(fmt::format("joint fault ({}, {} so far on joint {} {}): {}", doing, j.status.faults,
                    int(j.config.number), j.config.name, f.message));
}

void ArmController::examine_faults(Joint& j, const std::string& why) {
  const int n = j.config.number;
  auto read = master_.read_diagnostics(n);
  if (!read) {
    log(fmt::format("joint {} {} stopped following ({}); its faults could not be read: {}", n, j.config.name,
                    why, read.error().message));
    return;
  }
  const joint_bus::JointDiagnostics& diag = read.value();
  const joint_bus::JointDiagnostics* d = &diag;
  ++stats_.fault_reads;
  j.status.diagnostic_words = {d->faults, d->bus_events_lost, d->encoder_edges_lost, d->uart_errors,
                               d->reset_cause, d->abandoned_transactions, d->settings};
  j.status.faults_read_at = clock().now();
  const bool first = j.status.diagnostics.empty() || j.status.joint_faults != d->faults;
  j.status.joint_faults = d->faults;
  j.status.diagnostics = joint_bus::describe(diag);
  if (d->runaway()) ++stats_.runaway_faults;
  if (d->following_error()) ++stats_.following_error_faults;
  if (!first) return;  // re-read, nothing new: no second log line
  log(fmt::format("joint {} {} stopped following ({}); {}{}", n, j.config.name, why, j.status.diagnostics,
                  d->faults != 0 ? std::string("; fix the cause, then `armctl arm clear-faults` (JointFaultClear)")
                                 : std::string()));
}

void ArmController::lost_following(Joint& j, const std::string& why) {
  j.status.following = false;
  if (j.status.following_lost < 0xFFFF) ++j.status.following_lost;
  ++stats_.following_lost;
  examine_faults(j, why);
}

rc::JointFaultReport ArmController::joint_faults(ServoId servo) const {
  const Joint& j = at(servo);
  rc::JointFaultReport r;
  r.servo = servo;
  r.answering = j.status.answering;
  r.following = j.status.following;
  r.words_read = !j.status.diagnostics.empty();
  r.behind_ramp = false;  // the daemon does not stop a move on a stall (docs/arm-controller.md)
  r.last_failure = j.last_failure ? static_cast<std::uint16_t>(joint_bus::spec_code(j.last_failure->first)) : 0;
  r.following_lost = j.status.following_lost;
  r.words = j.status.diagnostic_words;
  r.words[joint_bus::diagnostic_faults] = j.status.joint_faults;  // 0 once it follows again
  return r;
}

rc::JointFaultClearReply ArmController::clear_joint_faults(ServoId servo, TimePoint now) {
  advance_to(now);
  Joint& j = at(servo);
  const TimePoint bus_now = clock().now();
  // A cleared joint holds where it is (its target := its position): the move it belongs to
  // (the joints planned to arrive with it) would go on without it, so it stops first.
  if (j.status.target && j.status.arrive_at > bus_now) {
    const TimePoint arrive = j.status.arrive_at;
    for (auto& other : joints_) {
      if (!other.status.target || other.status.arrive_at != arrive) continue;
      cancel_ops(other.config.number);
      schedule(bus_now, other.config.number, OpKind::speed, 0);
      other.status.target.reset();
    }
  }
  cancel_ops(servo);
  j.status.jogging = false;
  j.status.target.reset();
  std::optional<Error> failure;
  timed([&] {
    if (auto r = master_.clear_faults(servo); !r) failure = r.error();
  });
  if (failure) {
    note_fault(j, *failure, "clear_faults");
    const joint_bus::JointFailure* f = joint_bus::joint_failure(*failure);
    const int code = f != nullptr ? f->code() : 0;
    return rc::JointFaultClearReply{servo, static_cast<std::uint16_t>(code != 0 ? code : joint_bus::status_no_answer)};
  }
  note_success(j);
  j.model.forget();  // holds where it is: the next move plans from its poll
  j.status.following = true;
  j.status.joint_faults = 0;
  j.status.diagnostics.clear();
  j.status.diagnostic_words = {};
  log(fmt::format("joint {} ({}): faults cleared", int(servo), j.config.name));
  return rc::JointFaultClearReply{servo, static_cast<std::uint16_t>(joint_bus::success_status(joint_bus::cmd_clear_faults))};
}

void ArmController::run_op(const Op& op) {
  Joint& j = at(op.joint);
  ++stats_.commands;
  const char* name = "";
  std::optional<Error> failure;
  timed([&] {
    Status r = Ok{};
    switch (op.kind) {
      case OpKind::loop_on: name = "set_pid_state 1"; r = master_.set_pid_state(op.joint, true); break;
      case OpKind::loop_off: name = "set_pid_state 0"; r = master_.set_pid_state(op.joint, false); break;
      case OpKind::speed: name = "set_speed"; r = master_.set_speed(op.joint, op.value); break;
      case OpKind::drive_to: name = "drive_to"; r = master_.drive_to(op.joint, op.value); break;
    }
    if (!r) failure = r.error();
  });
  if (failure) {
    ++stats_.command_failures;
    j.model.forget();  // it may or may not have taken effect
    note_fault(j, *failure, name);
    const joint_bus::JointFailure* jf = joint_bus::joint_failure(*failure);
    if (op.kind == OpKind::drive_to && jf != nullptr && jf->kind == joint_bus::FailureKind::bad_data &&
        j.status.following) {
      // A joint holding a fault refuses every drive with 940: find out why.
      lost_following(j, fmt::format("drive_to {} refused", op.value));
    }
    if (op.kind == OpKind::speed || op.kind == OpKind::loop_on) {
      // The drive that should follow would run at a wrong speed or not at all: drop it.
      std::erase_if(ops_, [&](const Op& o) { return o.joint == op.joint && o.kind == OpKind::drive_to; });
      j.status.target.reset();
    }
  } else {
    note_success(j);
    const TimePoint t = effect_instant();
    switch (op.kind) {
      case OpKind::loop_on: j.model.rest_at(j.status.clicks.value_or(0), t); break;  // holds where it is
      case OpKind::loop_off: j.model.forget(); break;
      case OpKind::speed: j.model.set_speed(op.value, t); break;
      case OpKind::drive_to: j.model.drive_to(op.value, t); break;
    }
  }
}

void ArmController::poll_next() {
  Joint& j = joints_[poll_index_];
  ++stats_.polls;
  timed([&] {
    auto r = master_.get_position(j.config.number);
    if (r) {
      j.status.clicks = *r;
      j.status.read_at = clock().now();
      ++j.status.reads;
      note_success(j);
      if (j.model.known() && j.status.loop_on) {
        const int planned = j.model.setpoint_clicks_at(j.status.read_at);
        const int gap = std::abs(*r - planned);
        stats_.max_model_gap = std::max(stats_.max_model_gap, double(gap));
        const std::string why = fmt::format("at {} clicks, planned {}", *r, planned);
        if (gap > kNotFollowingClicks && j.status.following) {
          lost_following(j, why);
        } else if (gap > kNotFollowingClicks && j.status.joint_faults == 0 &&
                   clock().now() - j.status.faults_read_at >= kFaultRecheck) {
          // Still off its plan with no fault yet: the joint may raise one any moment (its
          // runaway and following-error checks take 100 and 500 ms).
          examine_faults(j, why);
        } else if (gap <= kNotFollowingClicks / 2) {
          j.status.following = true;
          j.status.joint_faults = 0;  // following again: its faults were cleared
        }
      }
    } else {
      ++stats_.poll_failures;
      note_fault(j, r.error(), "get_position");
    }
  });
  if (++poll_index_ == joints_.size()) {
    poll_index_ = 0;
    ++stats_.sweeps;
  }
}

void ArmController::wait_until(TimePoint t) {
  const TimePoint now = clock().now();
  if (t > now) joint_bus::idle(link_, t - now);
}

void ArmController::service(TimePoint limit) {
  const TimePoint now = clock().now();
  advance_to(now);
  if (!ops_.empty() && ops_.front().due <= now) {
    Op op = ops_.front();
    ops_.erase(ops_.begin());
    run_op(op);
    return;
  }
  if (!ops_.empty() && ops_.front().due - now < txn_estimate_) {
    // A poll now would make the next command late: keep the bus free for it.
    wait_until(std::min(limit, ops_.front().due));
    return;
  }
  poll_next();
}

}  // namespace armctl::arm_controller
