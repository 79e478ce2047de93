// Per-joint tuning of the position loop and what the loop asks of the H-bridge.
// Portable (C++14, no STL, no float): shared by the firmware and the host simulator.
#pragma once

#include <stdint.h>

namespace armctl {
namespace joint_bus {

// Units: clicks (4x quadrature counts), seconds, PWM counts. All integers so the AVR never
// touches floating point. begin() clamps every field into the range noted here (the ranges
// keep every fixed-point product inside int32; see docs/joint-controller.md).
struct JointTuning {
  int32_t max_speed_cps;   // velocity at set_speed 100 %, clicks/s          [1, 50000]
  int32_t max_accel_cps2;  // acceleration limit of the setpoint, clicks/s^2 [3906, 1000000]
  // PID gains in Q8 fixed point (value = gain * 256). Error in clicks, output in PWM counts.
  int32_t kp_q8;  // PWM counts per click of error                           [0, 65535]
  int32_t ki_q8;  // PWM counts per click of error per tick (1 ms)           [0, 65535]
  int32_t kd_q8;  // PWM counts per click/tick of measured speed (derivative on measurement)
                  //                                                         [0, 65535]
  int16_t pwm_max;  // full-scale duty (255 for the 8-bit timers of the ATmega328P) [1, 4095]
};

// The accepted ranges of the ramp fields (begin() clamps into them). Why these bounds:
// docs/joint-controller.md, "Tuning ranges".
const int32_t max_speed_cps_limit = 50000;
const int32_t min_accel_cps2_limit = 3906;  // 1 Q8 click/tick^2
const int32_t max_accel_cps2_limit = 1000000;

// A reasonable starting point for a 24 V DC joint with a ~2000 click/rev motor encoder
// behind the 20.23:1 gearbox. The simulator tunes per-joint gains against its motor model.
inline JointTuning default_tuning() {
  JointTuning t;
  t.max_speed_cps = 20000;
  t.max_accel_cps2 = 100000;
  t.kp_q8 = 4 * 256;     // 4 PWM counts per click
  t.ki_q8 = 8;           // 0.03 PWM counts per click per ms
  t.kd_q8 = 40 * 256;    // 40 PWM counts per click/ms
  t.pwm_max = 255;
  return t;
}

// What the H-bridge should do. duty > 0 drives "right" (D11/OC2A), duty < 0 drives "left"
// (D10/OC1B); |duty| <= pwm_max. The controller applies the joint's MotorPolarity
// (joint_options.hpp): with the original polarity, duty > 0 is what counts the encoder up.
// enable = false: H-bridge disabled (motor coasts), duty 0.
struct DriveOutput {
  int16_t duty;
  bool enable;
};

}  // namespace joint_bus
}  // namespace armctl
