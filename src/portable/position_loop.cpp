#include "portable/position_loop.hpp"

#include "portable/fixed_point.hpp"

namespace armctl {
namespace joint_bus {

namespace {
// Counts beyond +-2^21 clicks are clamped before conversion to Q8, so Q8 positions stay
// within +-2^29 and their differences within int32. 2 million clicks is some 1000 motor
// turns past the bus range: never reached.
const int32_t kCountLimit = INT32_C(1) << 21;

int32_t count_to_q8(int32_t count) {
  return clamp32(count, -kCountLimit, kCountLimit) * INT32_C(256);
}

JointTuning clamped(const JointTuning& t) {
  JointTuning c = t;
  // Ranges: docs/joint-controller.md "Tuning ranges" (what the SCARA joints need, and what
  // keeps the tick inside its cycle budget). They convert exactly to the ramp's bounds.
  c.max_speed_cps = clamp_setting(t.max_speed_cps, 1, max_speed_cps_limit);
  c.max_accel_cps2 = clamp_setting(t.max_accel_cps2, min_accel_cps2_limit, max_accel_cps2_limit);
  c.kp_q8 = clamp_setting(t.kp_q8, 0, INT32_C(65535));
  c.ki_q8 = clamp_setting(t.ki_q8, 0, INT32_C(65535));
  c.kd_q8 = clamp_setting(t.kd_q8, 0, INT32_C(65535));
  c.pwm_max = static_cast<int16_t>(clamp_setting(t.pwm_max, 1, 4095));
  return c;
}
}  // namespace

__attribute__((noinline)) int32_t clamp_setting(int32_t v, int32_t lo, int32_t hi) { return clamp32(v, lo, hi); }

void PositionLoop::begin(const JointTuning& tuning, int32_t count) {
  tuning_ = clamped(tuning);
  // (Both settings are clamped positive: fixed_point.hpp's conversions.)
  const int32_t top_speed_q8 = static_cast<int32_t>(speed_q8_per_tick(static_cast<uint32_t>(tuning_.max_speed_cps)));
  const int32_t accel_q8 = static_cast<int32_t>(accel_q8_per_tick2(static_cast<uint32_t>(tuning_.max_accel_cps2)));
  ramp_.configure(top_speed_q8, accel_q8);
  pid_.configure(tuning_.kp_q8, tuning_.ki_q8, tuning_.kd_q8, tuning_.pwm_max);
  speed_percent_ = 100;
  ramp_.set_speed_percent(speed_percent_);
  zone_ = 0;
  enabled_ = true;
  sync_to(count);
}

void PositionLoop::sync_to(int32_t count) {
  target_ = saturate_to_int16(count);
  ramp_.reset(count_to_q8(count));
  pid_.reset(count_to_q8(count));
}

DriveOutput PositionLoop::tick(int32_t count) {
  if (!enabled_) {
    // Loop off: the joint may be moved by hand; target follows so re-enabling holds here.
    sync_to(count);
    return DriveOutput{0, false};
  }
  const int32_t setpoint = ramp_.step(static_cast<int32_t>(target_) * 256);
  const int32_t measured = count_to_q8(count);
  error_q8_ = setpoint - measured;
  return DriveOutput{pid_.update(setpoint, static_cast<int16_t>(ramp_.velocity_q8()), measured), true};
}

void PositionLoop::set_enabled(bool on, int32_t count) {
  if (on == enabled_) return;  // set_pid_state 1 while on must not disturb the motion
  sync_to(count);
  enabled_ = on;
}

void PositionLoop::home() {
  // The caller zeroes the encoder count: position := 0, target := 0, setpoint at rest at 0,
  // integral cleared, derivative history at 0. The on/off state is kept.
  target_ = 0;
  ramp_.reset(0);
  pid_.reset(0);
}

bool PositionLoop::target_reached(int32_t count) const {
  const int32_t position = clamp32(count, -kCountLimit, kCountLimit);
  return abs32(static_cast<int32_t>(target_) - position) <= static_cast<uint32_t>(zone_);
}

}  // namespace joint_bus
}  // namespace armctl
