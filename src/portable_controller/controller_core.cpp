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
                           uint32_t bus_baud, uint32_t now_us, GroupMemory* groups,
                           GroupStore::Entry* directory, uint8_t entries) {
  joints_ = joints;
  count_ = count > max_joints ? max_joints : count;
  upstream_ = upstream;
  master_.begin(bus, bus_baud);
  op_count_ = 0;
  pending_count_ = 0;
  poll_index_ = 0;
  convert_ = no_convert;
  check_ = no_convert;
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
  if (have_groups_) {
    if (directory == nullptr || entries == 0) {
      directory = directory_;
      entries = GroupStore::mega_entries;
    }
    groups_.begin(groups, groups->size() - settings_bytes, directory, entries);
  }
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
    if (static_cast<int32_t>(due_us - op.due_us) < 0) {
      op.due_us = due_us;
      // Due sooner: ahead of the ops due after it (the queue stays in order of due time;
      // start_next() looks at its head only).
      for (uint8_t k = i; k > 0 && static_cast<int32_t>(ops_[k - 1].due_us - ops_[k].due_us) > 0; --k) {
        const Op moved = ops_[k];
        ops_[k] = ops_[k - 1];
        ops_[k - 1] = moved;
      }
    }
    return true;
  }
  return schedule(due_us, index, kind, value);
}

void ControllerCore::cancel_ops(uint8_t index, bool drives_only) {
  uint8_t kept = 0;
  for (uint8_t i = 0; i < op_count_; ++i) {
    // A read of the joint's diagnostic words is kept: a new move does not answer why it
    // stopped following.
    const bool drop = ops_[i].joint == joints_[index].number && !kept_through_moves(ops_[i].kind) &&
                      (!drives_only || ops_[i].kind == OpKind::drive_to);
    if (!drop) ops_[kept++] = ops_[i];
  }
  op_count_ = kept;
}

void ControllerCore::poll(uint32_t now_us) {
  last_now_us_ = now_us;
  if (have_groups_) service_groups();
  master_.poll(now_us);
  BusResult r = BusResult();
  if (master_.take_result(&r)) take_result(r, now_us);
  chain_poll(now_us);
  // Moves are planned between transactions (see plan_pending). Planning takes long enough
  // on the Mega that `now_us` is stale afterwards: the next transaction starts at the next
  // poll, with a fresh time (else its timeout would run from before the planning).
  if (!master_.busy()) {
    // Planning, in passes between two transactions: the models of the move's joints first,
    // a joint a pass, then the plan (each pass stays short enough for the receive ring).
    if (plan_due() && fold_pending(now_us)) {
      after_poll(now_us);
      return;
    }
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
  // Mega), done once the next joint is selected, while that joint prepares its READY, not
  // between the two transactions; nothing reads `position` before poll() returns. Its
  // check against the joint's plan (floating point while it moves: the ramp check) in the
  // next pass, which has nothing else to do (a transaction lasts many passes): each pass
  // stays under a word at 115200.
  if (convert_ == no_convert) {
    if (check_ != no_convert) {
      const uint8_t index = check_;
      check_ = no_convert;
      check_following(index, check_before_, now_us);  // may leave a ramp check for the next pass
    } else if (ramp_check_ != no_convert) {
      const uint8_t index = ramp_check_;
      ramp_check_ = no_convert;
      check_ramp(index, now_us);
    }
    return;
  }
  // (Transactions faster than passes, as scripted joints answer in host tests: the checks
  // still waiting are done first, so that none is skipped. On the Mega a transaction lasts
  // dozens of passes.)
  if (check_ != no_convert) {
    const uint8_t waiting = check_;
    check_ = no_convert;
    check_following(waiting, check_before_, now_us);
  }
  if (ramp_check_ != no_convert) {
    const uint8_t waiting = ramp_check_;
    ramp_check_ = no_convert;
    check_ramp(waiting, now_us);
  }
  const uint8_t index = convert_;
  convert_ = no_convert;
  JointState& s = state_[index];
  s.position = to_position(joints_[index].number, s.clicks);
  check_ = index;
  check_before_ = polled_before_;
}

bool ControllerCore::plan_due() const {
  // Moves streamed faster than they can be planned: the bus work of the last plan gets a
  // few transactions first (else, at 115200, plans of 8 ms each would follow each other
  // and no command would ever go out). Work due later (a part-way speed switch) does not
  // hold a plan back.
  return pending_count_ > 0 && (op_count_ == 0 || txns_since_plan_ >= min_txns_between_plans ||
                                !reached(last_now_us_, ops_[0].due_us));
}

bool ControllerCore::plan_pending(uint32_t now_us, bool now_or_never) {
  if (pending_count_ == 0) return false;
  if (!now_or_never && !plan_due()) return false;
  txns_since_plan_ = 0;
  const uint8_t n = pending_count_;
  pending_count_ = 0;
  plan_move(pending_, n, pending_ms_, now_us);
  return true;
}

void ControllerCore::start_next(uint32_t now_us) {
  if (count_ == 0) return;
  // Streamed moves keep commands due all the time: every few commands of a move a poll
  // still goes out (else no position is read while a host streams, ServoPositionRead
  // answers the positions from before the stream, and no joint is checked against its
  // plan). A halt (set_speed 0) never waits for one.
  const OpKind head = ops_[0].kind;
  const bool poll_first = op_count_ > 0 && commands_in_row_ >= max_commands_in_row &&
                          (head == OpKind::drive_to || head == OpKind::speed_switch ||
                           (head == OpKind::speed && ops_[0].value != 0));
  if (op_count_ > 0 && reached(now_us, ops_[0].due_us) && !poll_first) {
    if (commands_in_row_ < 255) ++commands_in_row_;
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
      case OpKind::clear_faults: command = jb::cmd_clear_faults; break;
    }
    if (txns_since_plan_ < 255) ++txns_since_plan_;
    inflight_is_op_ = true;
    inflight_kind_ = op.kind;
    inflight_value_ = op.value;
    inflight_index_ = static_cast<uint8_t>(index_of(op.joint));
    count_up(stats_.commands);
    master_.start(op.joint, command, op.value, now_us);
    return;
  }
  // A poll would delay a command due before it ends: keep the bus free for the command.
  if (!poll_first && op_count_ > 0 &&
      static_cast<int32_t>(ops_[0].due_us - now_us) < int32_t(master_.transaction_estimate_us()))
    return;
  commands_in_row_ = 0;
  inflight_is_op_ = false;
  ++stats_.polls;
  master_.start(joints_[poll_index_].number, jb::cmd_get_position, 0, now_us);
}

bool ControllerCore::may_chain_poll(uint32_t now_us) const {
  if (count_ == 0 || pending_count_ > 0 || playing_) return false;
  return op_count_ == 0 ||
         static_cast<int32_t>(ops_[0].due_us - now_us) > int32_t(2 * master_.transaction_estimate_us());
}

void ControllerCore::chain_poll(uint32_t now_us) {
  if (!may_chain_poll(now_us)) {
    master_.unchain();
    return;
  }
  // Behind a poll the next joint's; behind a command the joint whose poll is due.
  if (master_.result_pending() || !master_.busy() || master_.chained()) return;
  uint8_t index = poll_index_;
  if (!inflight_is_op_ && ++index == count_) index = 0;
  master_.chain(joints_[index].number, jb::cmd_get_position, 0);
}

void ControllerCore::note_model(uint8_t index, uint8_t kind, int16_t value, uint32_t at_us) {
  JointState& s = state_[index];
  if (!s.model_known) return;
  if (s.model_events == sizeof s.events / sizeof s.events[0]) {
    forget_model(index);  // more commands than a plan's between two plans: start afresh
    return;
  }
  s.events[s.model_events++] = ModelEvent{at_us, value, kind};
}

void ControllerCore::forget_model(uint8_t index) {
  state_[index].model_known = false;
  state_[index].model_events = 0;
}

void ControllerCore::rest_model(uint8_t index, float at, uint8_t percent, uint32_t now_us) {
  JointState& s = state_[index];
  const JointSetup& j = joints_[index];
  s.model = SetpointMotion{at, 0.0f, at, percent == model_unknown_percent ? 0.0f : ramp_speed(j.max_speed_cps, percent),
                           ramp_accel(j.max_accel_cps2)};
  s.model_percent = percent;
  s.model_events = 0;
  s.model_us = now_us;
  s.model_known = true;
  s.model_resting = true;
  s.model_arrives = false;
  s.phases = MotionPhases{};
  s.phases.x1 = at;
  s.phases.sign = 1.0f;
}

void ControllerCore::fold_model(uint8_t index, uint32_t now_us) {
  JointState& s = state_[index];
  const JointSetup& j = joints_[index];
  if (!s.model_known || !s.loop_on) {
    // Nothing known: at rest where it was polled (held: the start-up's set_speed 0), its
    // speed to be set by the move. (A joint whose loop is off gets loop-on first, which
    // anchors the model again where the joint then is.)
    rest_model(index, float(s.clicks), model_unknown_percent, now_us);
    return;
  }
  if (s.model_events == 0) return;
  if (s.planned && reached(now_us, s.plan_end_us + settled_us) && !queued(index, OpKind::drive_to) &&
      !queued(index, OpKind::speed) && !queued(index, OpKind::speed_switch) && !master_.busy()) {
    // Its move ended a while ago with nothing more on its way: its plan had it at rest on
    // its target by then (no arithmetic: the Mega computes floating point slowly).
    float target = s.model.target;
    uint8_t percent = s.model_percent;
    bool anchored = false;  // loop-on: not this shortcut
    for (uint8_t e = 0; e < s.model_events; ++e) {
      if (s.events[e].kind == model_drive) target = float(s.events[e].value);
      if (s.events[e].kind == model_speed) percent = static_cast<uint8_t>(s.events[e].value);
      if (s.events[e].kind == model_rest) anchored = true;
    }
    if (!anchored && target == float(s.plan_to) && percent != model_unknown_percent && percent != 0) {
      rest_model(index, target, percent, now_us);
      return;
    }
  }
  // The noted commands in the order they took effect (one after another on the bus). One
  // that took effect within a transaction of the one before is taken as if with it (a
  // moving joint's drive and speed): an evaluation and a shaping fewer.
  const uint32_t together_us = master_.transaction_estimate_us() + master_.word_time_us();
  bool shaped = true;  // s.phases are those of s.model
  for (uint8_t e = 0; e < s.model_events; ++e) {
    const ModelEvent& ev = s.events[e];
    const bool with_last = e > 0 && static_cast<uint32_t>(ev.at_us - s.model_us) < together_us;
    if (!with_last) {
      if (!s.model_resting) {
        if (!shaped) s.phases = motion_phases(s.model);
        const SetpointState st =
            motion_at(s.model, s.phases, float(static_cast<int32_t>(ev.at_us - s.model_us)) * 1e-6f);
        s.model.x0 = st.x;
        s.model.v0 = st.v;
      }
      s.model_us = ev.at_us;
    }
    if (ev.kind == model_drive) {
      s.model.target = float(ev.value);
    } else if (ev.kind == model_speed) {
      s.model_percent = static_cast<uint8_t>(ev.value);
      s.model.limit = ramp_speed(j.max_speed_cps, s.model_percent);
    } else {
      s.model.x0 = float(ev.value);
      s.model.v0 = 0.0f;
      s.model.target = float(ev.value);
    }
    s.model_resting = s.model.v0 == 0.0f && (s.model.x0 == s.model.target || s.model.limit == 0.0f);
    shaped = false;
  }
  s.model_events = 0;
  s.phases = motion_phases(s.model);
  const float arrival_s = motion_arrival_s(s.phases);
  s.model_arrives = !s.model_resting && arrival_s >= 0.0f && arrival_s < 1000.0f;
  if (s.model_arrives) s.model_rest_us = s.model_us + static_cast<uint32_t>(arrival_s * 1e6f);
}

bool ControllerCore::fold_pending(uint32_t now_us) {
  for (uint8_t k = 0; k < pending_count_; ++k) {
    const JointState& s = state_[pending_[k].index];
    if (s.model_known && s.loop_on && s.model_events > 0) {
      fold_model(pending_[k].index, now_us);
      check_stream(pending_[k].index, now_us);  // a stall stops every move, the pending one too
      return true;
    }
  }
  return false;
}

void ControllerCore::note_fault(uint8_t index, int16_t status) {
  JointState& s = state_[index];
  count_up(s.faults);
  s.answering = false;
  s.planned = false;  // what it does now is not known
  forget_model(index);
  s.last_fault = status;
}

void ControllerCore::take_result(const BusResult& r, uint32_t now_us) {
  handle_result(r, now_us);
  if (!r.chained_started) return;
  // The chained poll (chain_poll) is the transaction under way now.
  commands_in_row_ = 0;
  inflight_is_op_ = false;
  ++stats_.polls;
}

void ControllerCore::handle_result(const BusResult& r, uint32_t now_us) {
  const int8_t found = index_of(r.joint);
  if (found < 0) return;
  const uint8_t index = static_cast<uint8_t>(found);
  JointState& s = state_[index];
  if (!inflight_is_op_) {
    if (r.ok) {
      polled_before_ = s.read ? s.clicks : r.response;
      s.clicks = r.response;
      // Its RESPONSE came before the select fell and STATUS came back (two words).
      s.read_us = now_us - 2 * master_.word_time_us();
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
  if (inflight_kind_ == OpKind::clear_faults) {
    faults_cleared(index, r);
    return;
  }
  if (r.ok) {
    s.answering = true;
    if (inflight_kind_ == OpKind::loop_on) s.loop_on = true;
    // The model learns what took effect: a command's DATA crossed the wire a STATUS word
    // (and the joint's turnaround) before this result.
    const uint32_t effect_us = now_us - master_.word_time_us();
    switch (inflight_kind_) {
      case OpKind::drive_to: note_model(index, model_drive, inflight_value_, effect_us); break;
      case OpKind::speed:
      case OpKind::speed_switch: note_model(index, model_speed, inflight_value_, effect_us); break;
      case OpKind::loop_on: note_model(index, model_rest, s.clicks, effect_us); break;
      case OpKind::loop_off: forget_model(index); break;
      default: break;
    }
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
    case rc_joint_fault_clear:
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
    case rc_joint_fault_clear: on_joint_fault_clear(data, length, now_us); return;
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

bool ControllerCore::queued(uint8_t index, OpKind kind) const {
  for (uint8_t i = 0; i < op_count_; ++i)
    if (ops_[i].joint == joints_[index].number && ops_[i].kind == kind) return true;
  return false;
}

bool ControllerCore::in_flight(uint8_t index, OpKind kind) const {
  return master_.busy() && inflight_is_op_ && inflight_index_ == index && inflight_kind_ == kind;
}

void ControllerCore::want_speed(uint8_t index, uint8_t percent, uint32_t due_us) {
  const JointState& s = state_[index];
  // Already at that speed (and no other on its way): a transaction saved for the drives.
  if (!queued(index, OpKind::speed) && !in_flight(index, OpKind::speed) &&
      !in_flight(index, OpKind::speed_switch) && s.model_known && s.model_percent == percent)
    return;
  upsert(due_us, index, OpKind::speed, percent);
}

void ControllerCore::want_drive(uint8_t index, int16_t clicks, uint32_t due_us) {
  const JointState& s = state_[index];
  if (!queued(index, OpKind::drive_to) && !in_flight(index, OpKind::drive_to) && s.model_known &&
      s.model.target == float(clicks))
    return;
  upsert(due_us, index, OpKind::drive_to, clicks);
}

void ControllerCore::plan_move(const Target* targets, uint8_t n, uint16_t time_ms, uint32_t now_us) {
  // Each joint starts from its setpoint as its model has it (docs/mega-controller.md,
  // "Moving start"). A joint at rest on its target starts from rest: bus order loop-on for
  // joints that were off, every speed, then the drives. A joint at rest does not move on a
  // speed change, so only the drives start motion; joint k's drive can take effect
  // `effect[k]` after now at the earliest; each gets the smallest whole percent that
  // arrives in time, and its drive is delayed so that its profile ends at the common
  // instant. The 1 % steps of set_speed are absorbed by a second set_speed, one percent
  // slower, part-way through (switch_time_s), not by delaying the drive: a delay of up to
  // 1/p of the move would leave a slow joint standing for seconds, and a stop in that time
  // would find it never started.
  // A joint still moving (or held short of its target by set_speed 0) gets its drive_to
  // first, at once (the moving joints take the first bus slots): a speed change first would
  // push it on toward its old target, and a delayed drive would let it run on there. Its
  // speed follows (only if it changes), the smallest percent that brings its ramp, from
  // where the model puts it when the drive takes effect, to rest on the new target in time.
  // The joints starting from rest arrive together: at the time asked, or later if one
  // cannot make it (as an xArm stretches a move to its servos' limits). A joint still
  // moving arrives at the time asked or as soon as it can (then at 100 %: one that fell
  // behind a streamed target catches up), not held back for the others (below).
  const uint32_t txn = master_.transaction_estimate_us();
  // drive_to takes effect once READY, COMMAND and DATA (3 words) have crossed the wire.
  const float latency_s = float(3 * master_.word_time_us()) * 1e-6f;
  const float txn_s = float(txn) * 1e-6f;
  uint8_t loop_ons = 0;
  bool moving[max_joints];
  bool idle[max_joints];  // at rest on this very target: nothing to send
  float effect_s[max_joints];
  float distance[max_joints];
  float from[max_joints];
  float fastest_s[max_joints];
  float arrive_k[max_joints];  // a moving joint's own arrival
  SetpointMotion start[max_joints];  // a moving joint's, when its drive takes effect
  MotionPhases phases[max_joints];   // those of `start` at 100 %
  uint8_t movers = 0, resting = 0;
  for (uint8_t k = 0; k < n; ++k) {
    const uint8_t index = targets[k].index;
    JointState& st = state_[index];
    if (!st.loop_on) ++loop_ons;
    fold_model(index, now_us);  // (usually done already, a joint a pass: fold_pending)
    // Come to rest on its target since: at rest there from now on.
    if (st.model_arrives && reached(now_us, st.model_rest_us))
      rest_model(index, st.model.target, st.model_percent, now_us);
    from[k] = st.model_resting ? st.model.x0 : st.model.target;  // moving: set below
    moving[k] = !st.model_resting || st.model.x0 != st.model.target;
    idle[k] = !moving[k] && st.loop_on && st.model.x0 == float(targets[k].clicks);
    if (moving[k]) ++movers;
    else if (!idle[k]) ++resting;
  }
  const float asked_s = float(time_ms) * 0.001f;
  float arrive_s = asked_s;
  // Per joint, once (each a 32-bit division on the Mega): its ramp's acceleration and top speed.
  float accel_k[max_joints];
  float top_k[max_joints];
  for (uint8_t k = 0; k < n; ++k) {
    const JointSetup& j = joints_[targets[k].index];
    accel_k[k] = ramp_accel(j.max_accel_cps2);
    top_k[k] = ramp_speed(j.max_speed_cps, 100);
  }
  uint8_t mover = 0, rester = 0;
  for (uint8_t k = 0; k < n; ++k) {
    const JointSetup& j = joints_[targets[k].index];
    const float accel = accel_k[k];
    const float top = top_k[k];
    fastest_s[k] = 0.0f;
    if (moving[k]) {
      effect_s[k] = float(loop_ons + mover++) * txn_s + latency_s;
      const JointState& st = state_[targets[k].index];
      const SetpointState then =
          motion_at(st.model, st.phases, float(static_cast<int32_t>(now_us - st.model_us)) * 1e-6f + effect_s[k]);
      from[k] = then.x;
      start[k] = SetpointMotion{then.x, then.v, float(targets[k].clicks), top, accel};
      phases[k] = motion_phases(start[k]);
      fastest_s[k] = motion_arrival_s(phases[k]);
      const float d = float(targets[k].clicks) - then.x;
      distance[k] = d < 0.0f ? -d : d;
    } else {
      // Behind the moving joints' drives and the speeds (a moving joint's speed usually stays).
      effect_s[k] = float(loop_ons + movers + resting + rester++) * txn_s + latency_s;
      const float d = float(targets[k].clicks) - from[k];
      distance[k] = d < 0.0f ? -d : d;
      if (!idle[k]) fastest_s[k] = shortest_time_s(distance[k], j.max_speed_cps, accel);
    }
    // The joints that start from rest arrive together, at the time asked or when the last
    // of them can. A moving joint arrives at the time asked, or as soon as it can: moves
    // that find joints moving are streamed, and a joint made to wait for a slower one (or
    // for one that must brake through its target and come back, which streamed targets,
    // closer together than a joint's stopping distance, often ask) falls behind its stream.
    if (!idle[k] && !moving[k] && effect_s[k] + fastest_s[k] > arrive_s) arrive_s = effect_s[k] + fastest_s[k];
  }
  float end_s = arrive_s;  // the latest arrival of any joint
  for (uint8_t k = 0; k < n; ++k) {
    if (!moving[k]) continue;
    arrive_k[k] = asked_s;
    if (effect_s[k] + fastest_s[k] > arrive_k[k]) arrive_k[k] = effect_s[k] + fastest_s[k];
    if (arrive_k[k] > end_s) end_s = arrive_k[k];
  }
  planned_ms_ = static_cast<uint32_t>(end_s * 1000.0f + 0.5f);
  for (uint8_t i = 0; i < max_joints; ++i) percent_[i] = 0;
  // Streamed moves come faster than a move's bus commands go out (seven speeds and seven
  // drives take 150 ms at 9600 baud, a point comes every 27 ms): a joint's speed and drive
  // still queued from the move before keep their place and take the new values, so every
  // joint gets its latest target in turn (cancelling them let the next move cancel its
  // commands again, and the joints last in bus order never moved). Commands that would
  // change nothing (the speed it runs at, the target it has) are not sent.
  for (uint8_t k = 0; k < n; ++k) {
    const uint8_t index = targets[k].index;
    uint8_t kept = 0;
    for (uint8_t i = 0; i < op_count_; ++i) {
      const Op& op = ops_[i];
      const bool drop = op.joint == joints_[index].number &&
                        (op.kind == OpKind::loop_off || op.kind == OpKind::speed_switch ||
                         (idle[k] && (op.kind == OpKind::speed || op.kind == OpKind::drive_to)));
      if (!drop) ops_[kept++] = op;
    }
    op_count_ = kept;
    if (!state_[index].loop_on) upsert(now_us, index, OpKind::loop_on, 1);
  }
  for (uint8_t k = 0; k < n; ++k)
    if (moving[k]) want_drive(targets[k].index, targets[k].clicks, now_us);
  for (uint8_t k = 0; k < n; ++k) {
    const uint8_t index = targets[k].index;
    JointState& s = state_[index];
    s.jogging = false;
    if (idle[k] || !moving[k]) continue;
    const float top = top_k[k];
    const float available_s = arrive_k[k] - effect_s[k];
    uint8_t percent = 100;
    if (effect_s[k] + fastest_s[k] + 0.005f < arrive_k[k]) {
      float limit = limit_for_arrival(start[k], phases[k], available_s, top);
      // A joint that must slow down: its slower set_speed goes out after every moving
      // joint's drive, `movers` transactions after its own, and until then it runs on at the
      // speed it has. Its percentage is chosen for what is left after that (without it such
      // a joint arrived early by those transactions: 153 ms of an 800 ms move at 9600). Not
      // for a joint that keeps or gains speed: in a stream its speed usually stays or is
      // already queued, and counting a lag there made a streamed LIN at 9600 through the
      // Mega 31 % worse. A few multiplications: the planning pass has no room for a second
      // model evaluation (mega_loop_worst).
      MotionPhases fast = phases[k];
      const float lag_s = float(movers) * txn_s;
      if (limit < fast.u1 && fast.brake_s <= 0.0f && available_s > lag_s && fast.distance > fast.u1 * lag_s) {
        fast.distance -= fast.u1 * lag_s;
        limit = limit_for_arrival(start[k], fast, available_s - lag_s, top);
      }
      const float p = ceilf(100.0f * limit / top);
      percent = p >= 100.0f ? 100 : p < 1.0f ? 1 : static_cast<uint8_t>(p);
    }
    percent_[index] = percent;
    want_speed(index, percent, now_us);
  }
  for (uint8_t k = 0; k < n; ++k) {
    const uint8_t index = targets[k].index;
    const JointSetup& j = joints_[index];
    if (idle[k] || moving[k]) continue;
    percent_[index] = percent_for(distance[k], arrive_s - effect_s[k], j.max_speed_cps, accel_k[k]);
    want_speed(index, percent_[index], now_us);
    state_[index].loop_on = true;
  }
  for (uint8_t k = 0; k < n; ++k) {
    const uint8_t index = targets[k].index;
    const JointSetup& j = joints_[index];
    JointState& s = state_[index];
    const float accel = accel_k[k];
    const uint8_t percent = percent_[index];
    float start_s = effect_s[k] - latency_s;
    float switch_s = 0.0f;
    if (!idle[k] && !moving[k]) {
      const float speed = float(j.max_speed_cps) * float(percent) * 0.01f;
      const float available_s = arrive_s - effect_s[k];
      float ramp_s = distance[k] > 0.0f ? shortest_time_s(distance[k], speed, accel) : 0.0f;
      if (percent > 1 && available_s - ramp_s > 0.003f &&
          switch_time_s(distance[k], available_s, speed, float(j.max_speed_cps) * float(percent - 1) * 0.01f, accel,
                        &switch_s)) {
        ramp_s = available_s;  // the drive at once, the slower speed from switch_s on
      }
      start_s = arrive_s - ramp_s - latency_s;
      if (start_s < 0.0f) start_s = 0.0f;
      want_drive(index, targets[k].clicks, now_us + static_cast<uint32_t>(start_s * 1e6f));
      if (switch_s > 0.0f) {
        schedule(now_us + static_cast<uint32_t>((start_s + switch_s) * 1e6f), index, OpKind::speed_switch,
                 static_cast<int16_t>(percent - 1));
      }
    }
    // A joint still moving may be anywhere near `from` and run on while it turns: v^2 / 2a
    // at its full speed.
    const float v = moving[k] ? float(j.max_speed_cps) : 0.0f;
    const float over = v * v / (2.0f * accel);
    s.planned = true;
    s.plan_from = static_cast<int16_t>(from[k] < 0.0f ? from[k] - 0.5f : from[k] + 0.5f);
    s.plan_to = targets[k].clicks;
    s.plan_start_us = now_us + static_cast<uint32_t>((start_s + latency_s) * 1e6f);
    s.plan_end_us = now_us + static_cast<uint32_t>((moving[k] ? arrive_k[k] : arrive_s) * 1e6f);
    s.plan_slack = over > 30000.0f ? 30000 : static_cast<uint16_t>(over);
    // The ramp check needs a ramp from rest; the slower speed keeps its model a lower bound.
    s.ramp_armed = false;
    s.behind_ramp = false;
    s.left_plan = false;
    s.ramp_percent = moving[k] || idle[k] ? 0 : switch_s > 0.0f ? static_cast<uint8_t>(percent - 1) : percent;
    if (s.ramp_percent != 0)
      s.ramp = ramp_shape(distance[k], float(j.max_speed_cps) * float(s.ramp_percent) * 0.01f, accel);
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

void ControllerCore::link_lost(uint32_t now_us) {
  stop_playing(true);
  halt(now_us);
  for (uint8_t i = 0; i < count_; ++i) state_[i].answering = false;
}

void ControllerCore::halt(uint32_t now_us) {
  // Every command dropped but a clear_faults a host waits for (it moves nothing).
  uint8_t kept = 0;
  for (uint8_t i = 0; i < op_count_; ++i)
    if (ops_[i].kind == OpKind::clear_faults) ops_[kept++] = ops_[i];
  op_count_ = kept;
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
