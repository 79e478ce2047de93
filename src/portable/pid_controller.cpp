#include "portable/pid_controller.hpp"

#include "portable/fixed_point.hpp"

namespace armctl {
namespace joint_bus {

namespace {
// Each term is kept within +-2^28 so that P + I + D can never overflow int32.
const int32_t kTermLimit = INT32_C(1) << 28;

int32_t input_limit(int32_t gain_q8) { return gain_q8 > 0 ? kTermLimit / gain_q8 : kTermLimit; }

uint16_t gain16(int32_t gain_q8) { return static_cast<uint16_t>(clamp32(gain_q8, 0, INT32_C(65535))); }

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
  output_max_q16_ = clamp32(output_max, 1, 4095) * INT32_C(65536);
  p_input_max_ = input_limit(kp_q8_);
  i_input_max_ = input_limit(ki_q8_);
  d_input_max_ = input_limit(kd_q8_);
  integral_q16_ = 0;
}

void PidController::reset(int32_t measurement_q8) {
  integral_q16_ = 0;
  previous_measurement_q8_ = measurement_q8;
}

int16_t PidController::update(int32_t setpoint_q8, int32_t setpoint_velocity_q8,
                              int32_t measurement_q8) {
  const int32_t error = setpoint_q8 - measurement_q8;
  const int32_t p = times_gain(kp_q8_, clamp_abs(error, p_input_max_));
  // Derivative on the measurement, not on the error: a jump of the setpoint or the target
  // changes nothing here, so it cannot kick the motor. The ramp's velocity (bounded, and
  // changing by at most the acceleration limit per tick) is the feedforward reference.
  const int32_t moved = measurement_q8 - previous_measurement_q8_;
  previous_measurement_q8_ = measurement_q8;
  const int32_t speed_error = setpoint_velocity_q8 - clamp_abs(moved, d_input_max_);
  const int32_t d = times_gain(kd_q8_, clamp_abs(speed_error, d_input_max_));

  // Anti-windup: integrate only while that does not push an output that is already at its
  // limit further into it, and keep the integral itself within the output range.
  const int32_t increment = times_gain(ki_q8_, clamp_abs(error, i_input_max_));
  const int32_t limit = output_max_q16_;
  int32_t sum = p + d + integral_q16_;
  const bool pushes_high = sum >= limit && increment > 0;
  const bool pushes_low = sum <= -limit && increment < 0;
  if (!pushes_high && !pushes_low) {
    integral_q16_ = clamp_abs(integral_q16_ + increment, limit);
    sum = p + d + integral_q16_;
  }
  return static_cast<int16_t>(round_q16(clamp_abs(sum, limit)));
}

}  // namespace joint_bus
}  // namespace armctl
