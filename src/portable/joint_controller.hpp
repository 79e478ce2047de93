// The joint controller: one joint's side of the joint bus plus its position loop.
// Portable code (C++14, no STL, no heap, no exceptions, no float): the same source runs in
// the ATmega328P firmware (firmware/) and in the host simulator (src/devices/joint_bus).
//
// It never blocks and never does I/O. The board layer (or the simulator) feeds it events
// and carries out what it asks for:
//   bus:     on_select(), on_rx_byte(), poll()  ->  next_tx_byte(), tx_enabled()
//   control: control_tick() at 1 kHz with the encoder count  ->  DriveOutput (PWM + enable)
// On the AVR, bus events come from the UART RX and pin-change interrupts and control_tick()
// from the 1 kHz timer; see firmware/README.md for which calls need interrupts masked.
#pragma once

#include <stdint.h>

#include "portable/joint_bus_codes.hpp"

namespace armctl {
namespace joint_bus {

// Per-joint tuning. Units: clicks (4x quadrature counts), seconds, PWM counts.
struct JointTuning {
  int32_t max_speed_cps;   // velocity at set_speed 100 %, clicks per second
  int32_t max_accel_cps2;  // acceleration limit of the setpoint, clicks per second^2
  // PID gains in Q8 fixed point (value = gain * 256), error in clicks, output in PWM counts.
  int32_t kp_q8;
  int32_t ki_q8;  // per tick (1 ms)
  int32_t kd_q8;  // per tick (1 ms), derivative on measurement
  int16_t pwm_max;  // full-scale duty (255 for 8-bit timers)
};

// What the H-bridge should do. duty > 0 drives "left" (D10/OC1B), duty < 0 drives "right"
// (D11/OC2A); |duty| <= pwm_max. enable = false means H-bridge disabled (motor coasts).
struct DriveOutput {
  int16_t duty;
  bool enable;
};

}  // namespace joint_bus
}  // namespace armctl
