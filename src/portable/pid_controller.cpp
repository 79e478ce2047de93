#include "portable/pid_controller.hpp"

#include "portable/fixed_point.hpp"

namespace armctl {
namespace joint_bus {

namespace {
// Each term is kept within +-2^28 so that P + I + D can never overflow int32.
const int32_t kTermLimit = INT32_C(1) << 28;

int32_t input_limit(int32_t gain_q8) { return gain_q8 > 0 ? kTermLimit / gain_q8 : kTermLimit; }
}  // namespace

void PidController::configure(int32_t kp_q8, int32_t ki_q8, int32_t kd_q8, int16_t output_max) {
  kp_q8_ = clamp32(kp_q8, 0, INT32_C(65535));
  ki_q8_ = clamp32(ki_q8, 0, INT32_C(65535));
  kd_q8_ = clamp32(kd_q8, 0, INT32_C(65535));
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
  const int32_t p = kp_q8_ * clamp32(error, -p_input_max_, p_input_max_);
  // Derivative on the measurement, not on the error: a jump of the setpoint or the target
  // changes nothing here, so it cannot kick the motor. The ramp's velocity (bounded, and
  // changing by at most the acceleration limit per tick) is the feedforward reference.
  const int32_t moved = measurement_q8 - previous_measurement_q8_;
  previous_measurement_q8_ = measurement_q8;
  const int32_t speed_error = setpoint_velocity_q8 - clamp32(moved, -d_input_max_, d_input_max_);
  const int32_t d = kd_q8_ * clamp32(speed_error, -d_input_max_, d_input_max_);

  // Anti-windup: integrate only while that does not push an output that is already at its
  // limit further into it, and keep the integral itself within the output range.
  const int32_t increment = ki_q8_ * clamp32(error, -i_input_max_, i_input_max_);
  const int32_t before = p + d + integral_q16_;
  const bool pushes_high = before >= output_max_q16_ && increment > 0;
  const bool pushes_low = before <= -output_max_q16_ && increment < 0;
  if (!pushes_high && !pushes_low) {
    integral_q16_ = clamp32(integral_q16_ + increment, -output_max_q16_, output_max_q16_);
  }

  const int32_t output = clamp32(p + d + integral_q16_, -output_max_q16_, output_max_q16_);
  return static_cast<int16_t>(round_q16(output));
}

}  // namespace joint_bus
}  // namespace armctl
