#include "portable_controller/controller_core.hpp"

#include <math.h>

#include "portable/joint_bus_codes.hpp"
#include "portable_controller/counting.hpp"
#include "portable_controller/ramp_model.hpp"
#include "portable_controller/rc_codes.hpp"

namespace armctl {
namespace controller {

namespace jb = ::armctl::joint_bus;

namespace {

const JointState no_joint{};


// a / b rounded to nearest, halves away from zero (b > 0).
int32_t divide_rounded(int32_t a, int32_t b) { return a >= 0 ? (a + b / 2) / b : -((-a + b / 2) / b); }


// The speed percent (1..100) that makes a joint at rest cover `distance` in `time_s`
// (a trapezoid: accelerate to v, cruise, decelerate; distance/v + v/accel = time).
uint8_t percent_for(float distance, float time_s, float speed, float accel) {
  if (distance <= 0.0f) return 1;
  const float a_t = accel * time_s;
  const float discriminant = a_t * a_t - 4.0f * accel * distance;
  if (discriminant <= 0.0f) return 100;
  const float v = (a_t - sqrtf(discriminant)) / 2.0f;
  const float percent = ceilf(100.0f * v / speed);
  if (percent >= 100.0f) return 100;
  return percent < 1.0f ? 1 : static_cast<uint8_t>(percent);
}

// A joint at rest covering `distance` in exactly `time_s` by starting at speed v1 and
// switching to v2 < v1 part-way (the slower percentage alone would arrive late, v1 alone
// early). Accelerating to v1, cruising, braking to v2 at the switch, cruising, braking to
// rest: the distance left at the switch is v1^2/2a + v2 t2, the time v1/a + t2, so the
// switch comes at (distance - v2 (time - v1/a)) / (v1 - v2) after the drive takes effect.
// False if the profile never cruises at v1 (its time then does not depend on the speed).
bool switch_time_s(float distance, float time_s, float v1, float v2, float accel, float* switch_s) {
  const float reach_s = v1 / accel;
  if (distance * accel < v1 * v1 || time_s < 2.0f * reach_s) return false;
  float t = (distance - v2 * (time_s - reach_s)) / (v1 - v2);
  if (t < reach_s) t = reach_s;                    // still accelerating: switch as it cruises
  if (t > time_s - reach_s) t = time_s - reach_s;  // not before it would brake anyway
  *switch_s = t;
  return true;
}

}  // namespace

void ControllerCore::begin(const JointSetup* joints, uint8_t count, BusPort* bus, UpstreamPort* upstream,
                           uint32_t bus_baud, uint32_t now_us, GroupMemory* groups) {
  joints_ = joints;
  count_ = count > max_joints ? max_joints : count;
  upstream_ = upstream;
  master_.begin(bus, bus_baud);
  op_count_ = 0;
  pending_count_ = 0;
  poll_index_ = 0;
  convert_ = no_convert;
  stats_ = CoreStats{};
  for (uint8_t i = 0; i < max_joints; ++i) {
    state_[i] = JointState{};
    state_[i].loop_on = true;
    state_[i].following = true;
    percent_[i] = 0;
  }
  for (uint8_t i = 0; i < count_; ++i) state_[i].position = to_position(joints_[i].number, 0);
  have_groups_ = groups != nullptr;
  memory_ = groups;
  info_index_ = 0;
  if (have_groups_) groups_.begin(groups, static_cast<uint16_t>(groups->size() - settings_bytes));
  load_settings();
  awaiting_ = Awaiting::nothing;
  download_stage_ = 0;
  playing_ = false;
  for (uint8_t g = 0; g < 255; ++g) speeds_[g] = 100;
  // Halting first: a joint still driving toward a target from before a reset stops at once.
  for (uint8_t i = 0; i < count_; ++i) schedule(now_us, i, OpKind::speed, 0);
  for (uint8_t i = 0; i < count_; ++i) schedule(now_us, i, OpKind::set_zone, joints_[i].zone);
}

int8_t ControllerCore::index_of(uint8_t joint) const {
  // Joints are usually configured in order (joint n at index n - 1): no search then.
  if (joint >= 1 && joint <= count_ && joints_[joint - 1].number == joint) return static_cast<int8_t>(joint - 1);
  for (uint8_t i = 0; i < count_; ++i)
    if (joints_[i].number == joint) return static_cast<int8_t>(i);
  return -1;
}

const JointState& ControllerCore::joint_state(uint8_t joint) const {
  const int8_t i = index_of(joint);
  return i < 0 ? no_joint : state_[i];
}

uint8_t ControllerCore::planned_percent(uint8_t joint) const {
  const int8_t i = index_of(joint);
  return i < 0 ? 0 : percent_[i];
}

namespace {
// Position (possibly offset beyond 0..1000) -> clicks on the joint's line, saturated.
int16_t map_to_clicks(const JointSetup& j, int32_t position) {
  const int32_t span = int32_t(j.clicks_at_1000) - j.clicks_at_0;
  const int32_t clicks = j.clicks_at_0 + divide_rounded(span * position, 1000);
  return static_cast<int16_t>(clicks < -32768 ? -32768 : clicks > 32767 ? 32767 : clicks);
}
}  // namespace

int16_t ControllerCore::to_clicks(uint8_t joint, uint16_t position) const {
  const int8_t i = index_of(joint);
  return i < 0 ? 0 : map_to_clicks(joints_[i], position);
}

int16_t ControllerCore::target_clicks(uint8_t index, uint16_t position) const {
  return map_to_clicks(joints_[index], int32_t(position) + state_[index].offset);
}

int16_t ControllerCore::to_position(uint8_t joint, int16_t clicks) const {
  const int8_t i = index_of(joint);
  if (i < 0) return 0;
  const JointSetup& j = joints_[i];
  const int32_t span = int32_t(j.clicks_at_1000) - j.clicks_at_0;
  if (span == 0) return 0;
  int32_t p = (int32_t(clicks) - j.clicks_at_0) * 1000;
  p = span > 0 ? divide_rounded(p, span) : divide_rounded(-p, -span);
  return static_cast<int16_t>(p);
}

// ------------------------------------------------------------------ operations

bool ControllerCore::schedule(uint32_t due_us, uint8_t index, OpKind kind, int16_t value) {
  if (op_count_ == max_ops) return false;
  // After every op due at or before this one: ops due together run in the order queued.
  uint8_t at = op_count_;
  while (at > 0 && static_cast<int32_t>(ops_[at - 1].due_us - due_us) > 0) {
    ops_[at] = ops_[at - 1];
    --at;
  }
  ops_[at] = Op{due_us, joints_[index].number, kind, value};
  ++op_count_;
  return true;
}

bool ControllerCore::upsert(uint32_t due_us, uint8_t index, OpKind kind, int16_t value) {
  for (uint8_t i = 0; i < op_count_; ++i) {
    Op& op = ops_[i];
    if (op.joint != joints_[index].number || op.kind != kind) continue;
    op.value = value;
    if (static_cast<int32_t>(due_us - op.due_us) < 0) op.due_us = due_us;
    return true;
  }
  return schedule(due_us, index, kind, value);
}

void ControllerCore::cancel_ops(uint8_t index, bool drives_only) {
  uint8_t kept = 0;
  for (uint8_t i = 0; i < op_count_; ++i) {
    // A read of the joint's diagnostic words is kept: a new move does not answer why it
    // stopped following.
    const bool drop = ops_[i].joint == joints_[index].number && ops_[i].kind != OpKind::diagnostic &&
                      (!drives_only || ops_[i].kind == OpKind::drive_to);
    if (!drop) ops_[kept++] = ops_[i];
  }
  op_count_ = kept;
}

void ControllerCore::poll(uint32_t now_us) {
  if (have_groups_) service_groups();
  master_.poll(now_us);
  BusResult r;
  if (master_.take_result(&r)) take_result(r, now_us);
  // Moves are planned between transactions (see plan_pending). Planning takes long enough
  // on the Mega that `now_us` is stale afterwards: the next transaction starts at the next
  // poll, with a fresh time (else its timeout would run from before the planning).
  if (!master_.busy()) {
    if (plan_pending(now_us)) {
      after_poll(now_us);
      return;
    }
    if (playing_ && reached(now_us, play_due_us_)) {
      play_next(now_us);
      after_poll(now_us);
      return;
    }
  }
  if (master_.can_start(now_us)) start_next(now_us);
  after_poll(now_us);
}

void ControllerCore::after_poll(uint32_t now_us) {
  // The polled reading in Robot Commands units (a 32-bit division, about 700 cycles on the
  // Mega) and its check against the joint's plan (floating point while it moves: the ramp
  // check), done once the next joint is selected, while that joint prepares its READY,
  // not between the two transactions. Nothing reads `position` before poll() returns.
  if (convert_ == no_convert) return;
  const uint8_t index = convert_;
  convert_ = no_convert;
  JointState& s = state_[index];
  s.position = to_position(joints_[index].number, s.clicks);
  check_following(index, polled_before_, now_us);
}

bool ControllerCore::plan_pending(uint32_t now_us, bool now_or_never) {
  if (pending_count_ == 0) return false;
  // Moves streamed faster than they can be planned: the bus work of the last plan gets a
  // few transactions first (else, at 115200, plans of 8 ms each would follow each other
  // and no command would ever go out).
  if (!now_or_never && op_count_ > 0 && txns_since_plan_ < min_txns_between_plans) return false;
  txns_since_plan_ = 0;
  const uint8_t n = pending_count_;
  pending_count_ = 0;
  plan_move(pending_, n, pending_ms_, now_us);
  return true;
}

void ControllerCore::start_next(uint32_t now_us) {
  if (count_ == 0) return;
  if (op_count_ > 0 && reached(now_us, ops_[0].due_us)) {
    const Op op = ops_[0];
    for (uint8_t i = 1; i < op_count_; ++i) ops_[i - 1] = ops_[i];
    --op_count_;
    int16_t command = jb::cmd_set_speed;
    switch (op.kind) {
      case OpKind::set_zone: command = jb::cmd_set_zone; break;
      case OpKind::loop_on:
      case OpKind::loop_off: command = jb::cmd_set_pid_state; break;
      case OpKind::speed:
      case OpKind::speed_switch: command = jb::cmd_set_speed; break;
      case OpKind::drive_to: command = jb::cmd_drive_to; break;
      case OpKind::diagnostic: command = jb::cmd_read_diagnostic; break;
    }
    if (txns_since_plan_ < 255) ++txns_since_plan_;
    inflight_is_op_ = true;
    inflight_kind_ = op.kind;
    inflight_value_ = op.value;
    count_up(stats_.commands);
    master_.start(op.joint, command, op.value, now_us);
    return;
  }
  // A poll would delay a command due before it ends: keep the bus free for the command.
  if (op_count_ > 0 && static_cast<int32_t>(ops_[0].due_us - now_us) < int32_t(master_.transaction_estimate_us()))
    return;
  inflight_is_op_ = false;
  ++stats_.polls;
  master_.start(joints_[poll_index_].number, jb::cmd_get_position, 0, now_us);
}

float ControllerCore::start_clicks(uint8_t index, uint32_t now_us) const {
  const JointState& s = state_[index];
  if (!s.planned || reached(now_us, s.plan_end_us)) return float(s.clicks);
  if (!reached(now_us, s.plan_start_us)) return float(s.plan_from);
  const float done = float(now_us - s.plan_start_us) / float(s.plan_end_us - s.plan_start_us);
  return float(s.plan_from) + (float(s.plan_to) - float(s.plan_from)) * done;
}

void ControllerCore::note_fault(uint8_t index, int16_t status) {
  JointState& s = state_[index];
  count_up(s.faults);
  s.answering = false;
  s.planned = false;  // what it does now is not known
  s.last_fault = status;
}

void ControllerCore::take_result(const BusResult& r, uint32_t now_us) {
  const int8_t found = index_of(r.joint);
  if (found < 0) return;
  const uint8_t index = static_cast<uint8_t>(found);
  JointState& s = state_[index];
  if (!inflight_is_op_) {
    if (r.ok) {
      polled_before_ = s.read ? s.clicks : r.response;
      s.clicks = r.response;
      // In position units once per poll (at the end of this poll(), after the next
      // transaction has started): a ServoPositionRead then only copies (seven divisions in
      // the reply's pass took the Mega 0.5 ms of its round trip).
      convert_ = index;
      s.read = true;
      s.answering = true;
      count_up(s.reads);
    } else {
      count_up(stats_.poll_failures);
      note_fault(index, r.status);
    }
    if (++poll_index_ == count_) {
      poll_index_ = 0;
      ++stats_.sweeps;
    }
    return;
  }
  if (r.ok) {
    s.answering = true;
    if (inflight_kind_ == OpKind::loop_on) s.loop_on = true;
    // Its ramp began when DATA arrived, a little before this answer: a late start keeps the
    // ramp check's model behind the joint's setpoint, never ahead.
    if (inflight_kind_ == OpKind::drive_to && s.planned && inflight_value_ == s.plan_to && s.ramp_percent != 0) {
      s.ramp_armed = true;
      s.ramp_start_us = now_us;
    }
    if (inflight_kind_ == OpKind::diagnostic && inflight_value_ >= 0 && inflight_value_ < jb::diagnostic_count) {
      s.diagnostics[inflight_value_] = static_cast<uint16_t>(r.response);
      if (inflight_value_ == jb::diagnostic_count - 1) {
        s.diagnostics_read = true;
        count_up(stats_.fault_reads);
        if ((s.diagnostics[jb::diagnostic_faults] & jb::fault_runaway) != 0) count_up(stats_.runaway_faults);
        if ((s.diagnostics[jb::diagnostic_faults] & jb::fault_following_error) != 0)
          count_up(stats_.following_error_faults);
      }
    }
    return;
  }
  count_up(stats_.command_failures);
  note_fault(index, r.status);
  // A joint holding a fault refuses every drive with 940: find out why.
  if (inflight_kind_ == OpKind::drive_to && r.status == jb::status_bad_data && s.following)
    lost_following(index, now_us);
  // A drive after a failed speed change or loop-on would run at the wrong speed, or not
  // at all: drop it.
  if (inflight_kind_ == OpKind::speed || inflight_kind_ == OpKind::loop_on) cancel_ops(index, true);
}

// ------------------------------------------------------------------ requests

void ControllerCore::on_frame(uint8_t command, const uint8_t* data, uint8_t length, uint32_t now_us) {
  count_up(stats_.frames);
  // A request that changes what the joints do comes after a move still waiting to be
  // planned: that move first, so that requests take effect in the order they came.
  switch (command) {
    case rc_multi_servo_off:
    case rc_servo_speed:
    case rc_group_run:
    case rc_group_erase: plan_pending(now_us, true); break;
    default: break;
  }
  switch (command) {
    case rc_multi_servo_move: on_move(data, length); return;
    case rc_servo_position_read: on_position_read(data, length); return;
    case rc_multi_servo_off: on_servo_off(data, length, now_us); return;
    case rc_group_stop:
      if (length != 0) break;
      stop_playing(false);
      halt(now_us);
      upstream_->send_frame(rc_group_stop, nullptr, 0);  // also when idle: a host waits for it
      return;
    case rc_servo_offset_adjust: on_offset_adjust(data, length); return;
    case rc_servo_offset_read: on_offset_read(data, length); return;
    case rc_servo_offset_write: on_offset_write(data, length); return;
    case rc_bus_servo_info_write: on_bus_servo_info_write(data, length); return;
    case rc_bus_servo_info_read: on_bus_servo_info_read(length); return;
    case rc_servo_speed: on_servo_speed(data, length, now_us); return;
    case rc_group_download:
      if (!have_groups_) break;
      on_group_download(data, length);
      return;
    case rc_group_run:
      if (!have_groups_) break;
      on_group_run(data, length, now_us);
      return;
    case rc_group_erase:
      if (!have_groups_) break;
      on_group_erase(data, length, now_us);
      return;
    case rc_group_speed:
      if (!have_groups_) break;
      on_group_speed(data, length);
      return;
    case rc_joint_fault_read: on_joint_fault_read(data, length); return;
    case rc_get_battery_voltage:
      if (length != 0) break;
      reply_u16(rc_get_battery_voltage, battery_mv_);
      return;
    default: break;
  }
  count_up(stats_.ignored_frames);
}

void ControllerCore::reply_u16(uint8_t command, uint16_t value) {
  const uint8_t data[2] = {static_cast<uint8_t>(value & 0xFFu), static_cast<uint8_t>(value >> 8)};
  upstream_->send_frame(command, data, 2);
}

ControllerCore::Check ControllerCore::check_targets(const uint8_t* servos, const uint16_t* positions, uint8_t n,
                                                    Target* out, uint8_t* moving) const {
  bool answering = true;
  *moving = 0;
  for (uint8_t k = 0; k < n; ++k) {
    const int8_t index = index_of(servos[k]);
    bool duplicate = false;
    for (uint8_t m = 0; m < k; ++m) duplicate = duplicate || servos[m] == servos[k];
    if (index < 0 || duplicate || (positions[k] != rc_null_position && positions[k] > rc_max_position))
      return Check::invalid;
    if (positions[k] == rc_null_position) continue;
    const JointSetup& j = joints_[index];
    const JointState& st = state_[index];
    if (positions[k] < st.position_min || positions[k] > st.position_max) return Check::invalid;
    const int16_t clicks = target_clicks(static_cast<uint8_t>(index), positions[k]);
    if (clicks < j.soft_min || clicks > j.soft_max) return Check::invalid;
    answering = answering && state_[index].answering && state_[index].read;
    out[(*moving)++] = Target{static_cast<uint8_t>(index), clicks};
  }
  return answering ? Check::ok : Check::not_answering;
}

void ControllerCore::on_move(const uint8_t* data, uint8_t length) {
  if (length < 3 || length != 3 + 3 * data[0] || data[0] > max_joints) {
    count_up(stats_.ignored_frames);
    return;
  }
  const uint8_t n = data[0];
  const uint16_t time_ms = rc_u16(data + 1);
  uint8_t servos[max_joints];
  uint16_t positions[max_joints];
  rc_read_targets(data + 3, n, servos, positions);
  Target targets[max_joints];
  uint8_t moving = 0;
  const Check check = time_ms > rc_max_move_ms ? Check::invalid : check_targets(servos, positions, n, targets, &moving);
  if (check == Check::invalid) {
    count_up(stats_.ignored_frames);
    return;
  }
  if (check == Check::not_answering) {
    // Refused whole: a synchronized move without one of its joints is not the move asked for.
    count_up(stats_.refused_moves);
    return;
  }
  count_up(stats_.moves);
  // Planned at the end of the transaction under way (poll): planning takes milliseconds on
  // the Mega, and a joint waiting that long mid-transaction for COMMAND would give up on it.
  // A move still waiting to be planned is merged with this one (streamed moves come faster
  // than a plan of seven joints takes on the Mega): the newest target of each joint, and
  // this move's time.
  for (uint8_t k = 0; k < moving; ++k) {
    uint8_t at = 0;
    while (at < pending_count_ && pending_[at].index != targets[k].index) ++at;
    pending_[at] = targets[k];
    if (at == pending_count_) ++pending_count_;
  }
  pending_ms_ = time_ms;
}

void ControllerCore::plan_move(const Target* targets, uint8_t n, uint16_t time_ms, uint32_t now_us) {
  // Bus order: loop-on for joints that were off, every speed, then the drives. A joint at
  // rest does not move on a speed change, so only the drives start motion. Joint k's drive
  // can take effect `effect[k]` after now at the earliest (behind the speeds and k drives);
  // the common arrival is the time asked, or later if a joint cannot make it. Each joint
  // gets the smallest whole percent that arrives in time, and its drive is delayed so that
  // its profile ends at the common instant. The 1 % steps of set_speed are absorbed by a
  // second set_speed, one percent slower, part-way through (switch_time_s), not by delaying
  // the drive: a delay of up to 1/p of the move would leave a slow joint standing for
  // seconds, and a stop in that time would find it never started.
  const uint32_t txn = master_.transaction_estimate_us();
  // drive_to takes effect once READY, COMMAND and DATA (3 words) have crossed the wire.
  const float latency_s = float(3 * master_.word_time_us()) / 1e6f;
  uint8_t loop_ons = 0;
  for (uint8_t k = 0; k < n; ++k)
    if (!state_[targets[k].index].loop_on) ++loop_ons;
  float effect_s[max_joints];
  float distance[max_joints];
  float from[max_joints];
  uint16_t slack[max_joints];
  float arrive_s = float(time_ms) / 1000.0f;
  for (uint8_t k = 0; k < n; ++k) {
    const JointSetup& j = joints_[targets[k].index];
    effect_s[k] = float(uint32_t(loop_ons + n + k) * txn) / 1e6f + latency_s;
    from[k] = start_clicks(targets[k].index, now_us);
    {
      // A joint still moving may be anywhere near `from` (a straight line, not its ramp) and
      // run on while it turns: v^2 / 2a at its full speed.
      const JointState& st = state_[targets[k].index];
      const bool moving = st.planned && !reached(now_us, st.plan_end_us);
      const float v = moving ? float(j.max_speed_cps) : 0.0f;
      const float over = v * v / (2.0f * ramp_accel(j.max_accel_cps2));
      slack[k] = over > 30000.0f ? 30000 : static_cast<uint16_t>(over);
    }
    const float d = float(targets[k].clicks) - from[k];
    distance[k] = d < 0.0f ? -d : d;
    const float earliest = effect_s[k] + shortest_time_s(distance[k], j.max_speed_cps, ramp_accel(j.max_accel_cps2));
    if (earliest > arrive_s) arrive_s = earliest;
  }
  planned_ms_ = static_cast<uint32_t>(arrive_s * 1000.0f + 0.5f);
  for (uint8_t i = 0; i < max_joints; ++i) percent_[i] = 0;
  // Streamed moves come faster than a move's bus commands go out (seven speeds and seven
  // drives take 150 ms at 9600 baud, a point comes every 27 ms): a joint's speed and drive
  // still queued from the move before keep their place and take the new values, so every
  // joint gets its latest target in turn (cancelling them let the next move cancel its
  // commands again, and the joints last in bus order never moved).
  for (uint8_t k = 0; k < n; ++k) {
    const uint8_t index = targets[k].index;
    uint8_t kept = 0;
    for (uint8_t i = 0; i < op_count_; ++i) {
      const Op& op = ops_[i];
      const bool drop = op.joint == joints_[index].number &&
                        (op.kind == OpKind::loop_off || op.kind == OpKind::speed_switch);
      if (!drop) ops_[kept++] = op;
    }
    op_count_ = kept;
    if (!state_[index].loop_on) upsert(now_us, index, OpKind::loop_on, 1);
  }
  for (uint8_t k = 0; k < n; ++k) {
    const uint8_t index = targets[k].index;
    const JointSetup& j = joints_[index];
    percent_[index] = percent_for(distance[k], arrive_s - effect_s[k], j.max_speed_cps, ramp_accel(j.max_accel_cps2));
    upsert(now_us, index, OpKind::speed, percent_[index]);
    state_[index].loop_on = true;
    state_[index].jogging = false;
  }
  for (uint8_t k = 0; k < n; ++k) {
    const uint8_t index = targets[k].index;
    const JointSetup& j = joints_[index];
    const float accel = ramp_accel(j.max_accel_cps2);
    const uint8_t percent = percent_[index];
    const float speed = float(j.max_speed_cps) * float(percent) / 100.0f;
    const float available_s = arrive_s - effect_s[k];
    float ramp_s = distance[k] > 0.0f ? shortest_time_s(distance[k], speed, accel) : 0.0f;
    float switch_s = 0.0f;
    if (percent > 1 && available_s - ramp_s > 0.003f &&
        switch_time_s(distance[k], available_s, speed, float(j.max_speed_cps) * float(percent - 1) / 100.0f, accel,
                      &switch_s)) {
      ramp_s = available_s;  // the drive at once, the slower speed from switch_s on
    }
    float start_s = arrive_s - ramp_s - latency_s;
    if (start_s < 0.0f) start_s = 0.0f;
    upsert(now_us + static_cast<uint32_t>(start_s * 1e6f), index, OpKind::drive_to, targets[k].clicks);
    if (switch_s > 0.0f) {
      schedule(now_us + static_cast<uint32_t>((start_s + switch_s) * 1e6f), index, OpKind::speed_switch,
               static_cast<int16_t>(percent - 1));
    }
    JointState& s = state_[index];
    s.planned = true;
    s.plan_from = static_cast<int16_t>(from[k] < 0.0f ? from[k] - 0.5f : from[k] + 0.5f);
    s.plan_to = targets[k].clicks;
    s.plan_start_us = now_us + static_cast<uint32_t>((start_s + latency_s) * 1e6f);
    s.plan_end_us = now_us + static_cast<uint32_t>(arrive_s * 1e6f);
    s.plan_slack = slack[k];
    // The ramp check needs a ramp from rest; the slower speed keeps its model a lower bound.
    s.ramp_armed = false;
    s.behind_ramp = false;
    s.ramp_percent = slack[k] != 0 ? 0 : switch_s > 0.0f ? static_cast<uint8_t>(percent - 1) : percent;
    if (s.ramp_percent != 0)
      s.ramp = ramp_shape(distance[k], float(j.max_speed_cps) * float(s.ramp_percent) / 100.0f, accel);
    s.plan_seen = s.clicks;
  }
}

void ControllerCore::on_position_read(const uint8_t* data, uint8_t length) {
  if (length < 1 || length != 1 + data[0] || data[0] > max_joints) {
    count_up(stats_.ignored_frames);
    return;
  }
  uint8_t reply[1 + 3 * max_joints];
  reply[0] = data[0];
  for (uint8_t k = 0; k < data[0]; ++k) {
    const uint8_t joint = data[1 + k];
    const int8_t index = index_of(joint);
    if (index < 0) {
      count_up(stats_.ignored_frames);
      return;
    }
    const uint16_t position = static_cast<uint16_t>(state_[index].position);
    reply[1 + 3 * k] = joint;
    reply[2 + 3 * k] = static_cast<uint8_t>(position & 0xFFu);
    reply[3 + 3 * k] = static_cast<uint8_t>(position >> 8);
  }
  upstream_->send_frame(rc_servo_position_read, reply, static_cast<uint8_t>(1 + 3 * data[0]));
}

void ControllerCore::on_servo_off(const uint8_t* data, uint8_t length, uint32_t now_us) {
  if (length < 1 || length != 1 + data[0] || data[0] > max_joints) {
    count_up(stats_.ignored_frames);
    return;
  }
  for (uint8_t k = 0; k < data[0]; ++k) {
    if (index_of(data[1 + k]) < 0) {
      count_up(stats_.ignored_frames);
      return;
    }
  }
  for (uint8_t k = 0; k < data[0]; ++k) {
    const uint8_t index = static_cast<uint8_t>(index_of(data[1 + k]));
    cancel_ops(index, false);
    schedule(now_us, index, OpKind::loop_off, 0);
    state_[index].loop_on = false;
    state_[index].planned = false;
    state_[index].jogging = false;
  }
}

void ControllerCore::halt(uint32_t now_us) {
  op_count_ = 0;
  pending_count_ = 0;
  // 0 % brings each joint's setpoint to rest at its acceleration limit and holds it there.
  for (uint8_t i = 0; i < count_; ++i) {
    schedule(now_us, i, OpKind::speed, 0);
    state_[i].planned = false;
    state_[i].jogging = false;
  }
}

}  // namespace controller
}  // namespace armctl
