// Joint faults (docs/mega-controller.md "Joint faults"): each poll of a joint with a plan
// is compared with the plan (check_following: where it may be, check_ramp: how far its
// setpoint ramp has come at least); a joint off its plan has its 7 diagnostic words read,
// and JointFaultRead (CMD 40, an armctl extension) answers what was found.
#include "portable/joint_bus_codes.hpp"
#include "portable_controller/controller_core.hpp"
#include "portable_controller/counting.hpp"
#include "portable_controller/ramp_model.hpp"
#include "portable_controller/rc_codes.hpp"

namespace armctl {
namespace controller {

namespace jb = ::armctl::joint_bus;

void ControllerCore::check_following(uint8_t index, int16_t before, uint32_t now_us) {
  JointState& s = state_[index];
  if ((s.behind_ramp || s.left_plan) && !s.planned) {
    // Its move was stopped; the joint may still raise a fault of its own (a stall that is a
    // runaway in its first moments, a following error).
    const bool fault_known = s.diagnostics_read && s.diagnostics[jb::diagnostic_faults] != 0;
    if (!fault_known && static_cast<uint32_t>(now_us - s.stalled_us) < stall_watch_us &&
        static_cast<uint32_t>(now_us - s.faults_read_us) >= fault_recheck_us)
      read_diagnostics(index, now_us);
    return;
  }
  if (!s.planned || !s.loop_on || s.jogging) return;
  const int32_t at = s.clicks;
  // Closer to its target than at the poll before: on its way, if late (the plan of a move
  // that starts while the joint moves is a straight line, not its ramp: a streamed move can
  // end later than planned). A faulted joint is at rest or runs away.
  int32_t was_off = int32_t(before) - s.plan_to;
  int32_t off = at - s.plan_to;
  if (was_off < 0) was_off = -was_off;
  if (off < 0) off = -off;
  const bool approaching = was_off - off >= approaching_clicks;
  int32_t gap = 0;
  const bool under_way = !reached(now_us, s.plan_end_us + settle_us);
  if (!under_way) {
    gap = at - s.plan_to;
    if (gap < 0) gap = -gap;
  } else {
    // Under way: anywhere between where its plan starts (the straight line's point and
    // the last poll, widened, for a joint still moving then, by what it may run on while
    // it turns at full speed) and its target: one that runs away is found when it leaves
    // that stretch.
    int32_t low = s.plan_to, high = s.plan_to;
    const int16_t from[2] = {s.plan_from, s.plan_seen};
    for (uint8_t i = 0; i < 2; ++i) {
      if (from[i] < low) low = from[i];
      if (from[i] > high) high = from[i];
    }
    if (s.plan_slack != 0) {
      low -= s.plan_slack;
      high += s.plan_slack;
    }
    gap = at < low ? low - at : at > high ? at - high : 0;
    // Inside that stretch, but behind the least its setpoint ramp has covered: stalled (a
    // joint outside it runs away, and is dealt with below). Floating point: in the next
    // main-loop pass (ControllerCore::after_poll), so that no pass exceeds a word at 115200.
    if (gap <= not_following_clicks && s.ramp_armed && !s.behind_ramp) ramp_check_ = index;
  }
  if (gap > not_following_clicks && !approaching) {
    if (s.following) {
      if (under_way) {
        // Out of its stretch mid-move (a runaway found before the ramp check saw it behind):
        // the move stops as for a stall, and its faults are read until one shows.
        s.left_plan = true;
        s.stalled_us = now_us;
        stop_move(index, now_us);
      }
      lost_following(index, now_us);
    } else if (!(s.diagnostics_read && s.diagnostics[jb::diagnostic_faults] != 0) &&
               static_cast<uint32_t>(now_us - s.faults_read_us) >= fault_recheck_us) {
      // Still off its plan with no fault yet: the joint may raise one any moment (its
      // runaway and following-error checks take 100 and 500 ms).
      read_diagnostics(index, now_us);
    }
  } else if (gap <= not_following_clicks / 2 && !s.following) {
    s.following = true;
    s.diagnostics[jb::diagnostic_faults] = 0;  // following again: its faults were cleared
  }
}

bool ControllerCore::check_ramp(uint8_t index, uint32_t now_us) {
  JointState& s = state_[index];
  if (!s.ramp_armed || s.behind_ramp || !s.planned) return false;
  // The reading is from the joint's RESPONSE, up to a transaction before now: judged at
  // that earlier instant, the model is behind the setpoint, never ahead. (Shaped when the
  // move was planned: here only multiplications, as this runs on every poll of a moving
  // joint, between two transactions.)
  const uint32_t read_us = now_us - master_.transaction_estimate_us();
  if (static_cast<int32_t>(read_us - s.ramp_start_us) <= 0) return false;
  const float least = ramp_covered(s.ramp, float(read_us - s.ramp_start_us) * 1e-6f);
  const int32_t moved = s.plan_to < s.plan_from ? int32_t(s.plan_from) - s.clicks : int32_t(s.clicks) - s.plan_from;
  // Tracking lag stays under 300 clicks on a healthy joint (docs/arm-controller.md).
  if (least - float(moved) <= float(not_following_clicks)) return false;
  return stalled(index, now_us, false);
}

bool ControllerCore::check_stream(uint8_t index, uint32_t now_us) {
  JointState& s = state_[index];
  if (!s.planned || s.ramp_percent != 0 || s.behind_ramp || s.jogging || !s.read || !s.model_known || !s.loop_on)
    return false;
  // The setpoint where the model had it when the joint was read: from the model's last
  // state (x0, v0 at model_us), at worst the acceleration's a dt^2 / 2 either way, as the
  // ramp never changes speed faster (a few multiplications: no phases evaluated).
  const float dt = float(static_cast<int32_t>(s.read_us - s.model_us)) * 1e-6f;
  if (dt > 0.3f || dt < -0.3f) return false;  // too far apart to bound usefully
  const float open = 0.5f * s.model.accel * dt * dt;
  float off = s.model.x0 + s.model.v0 * dt - float(s.clicks);
  if (off < 0.0f) off = -off;
  // Tracking lag stays under 300 clicks on a healthy joint (docs/arm-controller.md).
  if (off - open <= float(not_following_clicks)) return false;
  return stalled(index, now_us, true);
}

bool ControllerCore::stalled(uint8_t index, uint32_t now_us, bool every_move) {
  JointState& s = state_[index];
  s.behind_ramp = true;
  s.stalled_us = now_us;
  count_up(stats_.stalls);
  stop_move(index, now_us, every_move);  // first: the joints' set_speed 0 go out before the reads
  if (s.following) lost_following(index, now_us);
  return true;
}

void ControllerCore::stop_move(uint8_t index, uint32_t now_us, bool every_move) {
  // A synchronized move without one of its joints is not the move asked for (the reason a
  // move naming a dead joint is refused whole): every joint of it comes to rest where it
  // is, as GroupStop brings them. The stalled joint's setpoint stops too, so a freed joint
  // does not lunge after a setpoint far ahead.
  const uint32_t end_us = state_[index].plan_end_us;
  if (playing_) stop_playing(true);
  pending_count_ = 0;
  for (uint8_t i = 0; i < count_; ++i) {
    JointState& s = state_[i];
    if (!s.planned || (!every_move && s.plan_end_us != end_us)) continue;
    cancel_ops(i, false);
    schedule(now_us, i, OpKind::speed, 0);
    s.planned = false;
    s.ramp_armed = false;
  }
}

void ControllerCore::lost_following(uint8_t index, uint32_t now_us) {
  JointState& s = state_[index];
  s.following = false;
  count_up(s.following_lost);
  count_up(stats_.following_lost);
  read_diagnostics(index, now_us);
}

void ControllerCore::read_diagnostics(uint8_t index, uint32_t now_us) {
  for (uint8_t i = 0; i < op_count_; ++i)
    if (ops_[i].joint == joints_[index].number && ops_[i].kind == OpKind::diagnostic) return;  // under way
  JointState& s = state_[index];
  s.faults_read_us = now_us;
  s.diagnostics_read = false;
  for (uint8_t k = 0; k < jb::diagnostic_count; ++k) schedule(now_us, index, OpKind::diagnostic, k);
}

void ControllerCore::on_joint_fault_read(const uint8_t* data, uint8_t length) {
  const int8_t found = length == 1 ? index_of(data[0]) : -1;
  if (found < 0) {
    count_up(stats_.ignored_frames);
    return;
  }
  const JointState& s = state_[found];
  // servo, flags, last bus failure, following lost, the 7 diagnostic words.
  uint8_t reply[6 + 2 * jb::diagnostic_count];
  reply[0] = data[0];
  reply[1] = static_cast<uint8_t>((s.answering ? 1u : 0u) | (s.following ? 2u : 0u) | (s.diagnostics_read ? 4u : 0u) |
                                   (s.behind_ramp ? 8u : 0u));
  reply[2] = static_cast<uint8_t>(uint16_t(s.last_fault) & 0xFFu);
  reply[3] = static_cast<uint8_t>(uint16_t(s.last_fault) >> 8);
  reply[4] = static_cast<uint8_t>(s.following_lost & 0xFFu);
  reply[5] = static_cast<uint8_t>(s.following_lost >> 8);
  for (uint8_t k = 0; k < jb::diagnostic_count; ++k) {
    reply[6 + 2 * k] = static_cast<uint8_t>(s.diagnostics[k] & 0xFFu);
    reply[7 + 2 * k] = static_cast<uint8_t>(s.diagnostics[k] >> 8);
  }
  upstream_->send_frame(rc_joint_fault_read, reply, sizeof reply);
}

void ControllerCore::on_joint_fault_clear(const uint8_t* data, uint8_t length, uint32_t now_us) {
  const int8_t found = length == 1 ? index_of(data[0]) : -1;
  if (found < 0) {
    count_up(stats_.ignored_frames);
    return;
  }
  const uint8_t index = static_cast<uint8_t>(found);
  JointState& s = state_[index];
  // A cleared joint holds where it is (its target := its position): a move it belongs to
  // would go on without it, so that move stops first, as for a stall. A jog ends too.
  if (s.planned) stop_move(index, now_us);
  s.jogging = false;
  if (!schedule(now_us, index, OpKind::clear_faults, 0)) count_up(stats_.ignored_frames);  // queue full: no reply
}

void ControllerCore::faults_cleared(uint8_t index, const BusResult& r) {
  JointState& s = state_[index];
  if (r.ok) {
    s.answering = true;
    s.following = true;
    s.behind_ramp = false;
    s.left_plan = false;
    s.diagnostics_read = false;
    s.diagnostics[jb::diagnostic_faults] = 0;
    s.planned = false;
    s.ramp_armed = false;
    forget_model(index);  // at rest where it is: the next move plans from its poll
  } else {
    count_up(stats_.command_failures);
    note_fault(index, r.status);
  }
  const uint8_t reply[3] = {joints_[index].number, static_cast<uint8_t>(uint16_t(r.status) & 0xFFu),
                            static_cast<uint8_t>(uint16_t(r.status) >> 8)};
  upstream_->send_frame(rc_joint_fault_clear, reply, sizeof reply);
}

}  // namespace controller
}  // namespace armctl
