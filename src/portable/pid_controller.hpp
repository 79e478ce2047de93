// Fixed-point PID for the position loop: proportional and integral on the error,
// derivative on the measurement (no kick when the target jumps), integral clamped and
// frozen while the output saturates in the error's direction (anti-windup).
// The setpoint's own velocity, which comes from the ramp and so changes by at most the
// acceleration limit per tick, is fed forward through the same gain: the D term is
// kd * (setpoint velocity - measured velocity), so a moving setpoint is tracked without the
// lag that pure derivative-on-measurement damping would add, and still nothing kicks.
// Formats: error in Q8 clicks, gains in Q8, terms and output in Q16 PWM counts.
#pragma once

#include <stdint.h>

namespace armctl {
namespace joint_bus {

class PidController {
 public:
  // Gains in Q8 (0..65535), output limit in PWM counts (1..4095).
  void configure(int32_t kp_q8, int32_t ki_q8, int32_t kd_q8, int16_t output_max);
  // Forget integral and derivative history; the next update takes measurement_q8 as the
  // previous measurement (so it produces no derivative kick either).
  void reset(int32_t measurement_q8);
  // One tick. Positions in Q8 clicks within +-2^29, setpoint velocity in Q8 clicks/tick
  // (within +-12800, SetpointRamp::top_speed_max_q8). Returns the duty in PWM counts,
  // within +-output_max.
  int16_t update(int32_t setpoint_q8, int16_t setpoint_velocity_q8, int32_t measurement_q8);

  int32_t integral_q16() const { return integral_q16_; }

 private:
  // Gains fit 16 bits, so each product is a 16 x 32-bit multiply (cheaper on the AVR).
  uint16_t kp_q8_ = 0;
  uint16_t ki_q8_ = 0;
  uint16_t kd_q8_ = 0;
  int32_t output_max_q16_ = 0;
  // Largest |input| of each product that keeps the product within +-2^28.
  int32_t error_input_max_ = 0;  // for P and I: 2^28 / max(kp, ki)
  int16_t d_input_max_ = 0;  // also <= 32767 (the D input is 16-bit)
  int32_t integral_q16_ = 0;
  int32_t previous_measurement_q8_ = 0;
};

}  // namespace joint_bus
}  // namespace armctl
