#include "portable/pid_controller.hpp"

#include "portable/fixed_point.hpp"

namespace armctl {
namespace joint_bus {

namespace {
// Each term is kept within +-2^28 so that P + I + D can never overflow int32.
const int32_t kTermLimit = INT32_C(1) << 28;

__attribute__((noinline)) int32_t input_limit(int32_t gain_q8) {
  // Unsigned division (gains are 0..65535): one division routine less in the firmware.
  return gain_q8 > 0 ? static_cast<int32_t>(static_cast<uint32_t>(kTermLimit) / static_cast<uint32_t>(gain_q8))
                     : kTermLimit;
}

// Largest movement per tick the D term looks at (Q8): 64 clicks per tick.
const int32_t kMovedLimit = INT32_C(16384);

uint16_t gain16(int32_t gain_q8) { return static_cast<uint16_t>(clamp_setting(gain_q8, 0, INT32_C(65535))); }

// gain x input, |input| <= 2^28 / gain: a 16 x 32-bit product that fits int32.
inline int32_t times_gain(uint16_t gain, int32_t input) { return static_cast<int32_t>(gain) * input; }

// Symmetric clamp to [-limit, limit] (limit >= 0).
inline int32_t clamp_abs(int32_t v, int32_t limit) {
  if (v > limit) return limit;
  if (v < -limit) return -limit;
  return v;
}
}  // namespace

void PidController::configure(int32_t kp_q8, int32_t ki_q8, int32_t kd_q8, int16_t output_max) {
  kp_q8_ = gain16(kp_q8);
  ki_q8_ = gain16(ki_q8);
  kd_q8_ = gain16(kd_q8);
  output_max_q16_ = clamp_setting(output_max, 1, 4095) * INT32_C(65536);
  error_input_max_ = input_limit(kp_q8_ > ki_q8_ ? kp_q8_ : ki_q8_);
  d_input_max_ = static_cast<int16_t>(clamp_setting(input_limit(kd_q8_), 0, INT32_C(32767)));
  integral_q16_ = 0;
}

void PidController::reset(int32_t measurement_q8) {
  integral_q16_ = 0;
  previous_measurement_q8_ = measurement_q8;
}

int16_t PidController::update(int32_t setpoint_q8, int16_t setpoint_velocity_q8,
                              int32_t measurement_q8) {
  // One clamp serves P and I: |error| <= 2^28 / max(kp, ki) keeps both products within
  // +-2^28. (It only caps the integral's rate for errors beyond that, where P alone already
  // saturates the output: e.g. kp = 4 -> 2^20 / 4 clicks.)
  const int32_t error = clamp_abs(setpoint_q8 - measurement_q8, error_input_max_);
  const int32_t p = times_gain(kp_q8_, error);
  // Derivative on the measurement, not on the error: a jump of the setpoint or the target
  // changes nothing here, so it cannot kick the motor. The ramp's velocity (bounded, and
  // changing by at most the acceleration limit per tick) is the feedforward reference.
  // 16-bit from here: the movement in one tick is clamped to +-64 clicks (64,000 clicks/s,
  // beyond any speed the ramp runs), so speed_error stays within +-(12800 + 16384).
  const int32_t moved = measurement_q8 - previous_measurement_q8_;
  previous_measurement_q8_ = measurement_q8;
  const int16_t moved16 = static_cast<int16_t>(clamp_abs(moved, kMovedLimit));
  int16_t speed_error = static_cast<int16_t>(setpoint_velocity_q8 - moved16);
  if (speed_error > d_input_max_) speed_error = d_input_max_;
  if (speed_error < -d_input_max_) speed_error = static_cast<int16_t>(-d_input_max_);
  const int32_t d = static_cast<int32_t>(kd_q8_) * speed_error;  // 16 x 16-bit product

  // Anti-windup: integrate only while that does not push an output that is already at its
  // limit further into it, and keep the integral itself within the output range.
  const int32_t limit = output_max_q16_;
  int32_t sum = p + d + integral_q16_;
  if (ki_q8_ != 0) {  // ki = 0: the integral stays 0 (reset() cleared it); skip the product
    const int32_t increment = times_gain(ki_q8_, error);
    const bool pushes_high = sum >= limit && increment > 0;
    const bool pushes_low = sum <= -limit && increment < 0;
    if (!pushes_high && !pushes_low) {
      integral_q16_ = clamp_abs(integral_q16_ + increment, limit);
      sum = p + d + integral_q16_;
    }
  }
  return static_cast<int16_t>(round_q16(clamp_abs(sum, limit)));
}

}  // namespace joint_bus
}  // namespace armctl
