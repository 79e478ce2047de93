// Moves the loop's setpoint toward the target under a velocity limit and an acceleration
// limit (a trapezoidal profile computed one tick at a time), so a new target never makes
// the motor jump. Fixed point: positions and velocities in Q8 clicks (1/256 click),
// velocity per tick, acceleration per tick^2; one tick = 1 ms.
//
// Velocities and the acceleration are kept in 16 bits (top speed <= 12800 Q8 = 50,000
// clicks/s, acceleration <= 256 Q8 = 1,000,000 clicks/s^2; docs/joint-controller.md says why
// the SCARA joints never need more): on the AVR most of a tick is then 16-bit arithmetic.
#pragma once

#include <stdint.h>

namespace armctl {
namespace joint_bus {

class SetpointRamp {
 public:
  // Upper bounds of configure()'s arguments (values above are clamped to them).
  static const int16_t top_speed_max_q8 = 12800;  // 50,000 clicks/s
  static const int16_t accel_max_q8 = 256;        // 1,000,000 clicks/s^2

  // accel_q8: acceleration limit in Q8 clicks/tick^2 (1..accel_max_q8). top_speed_q8:
  // velocity at 100 % in Q8 clicks/tick (0..top_speed_max_q8).
  void configure(int32_t top_speed_q8, int32_t accel_q8);
  // Velocity limit as a percentage of the top speed (0..100; 0 holds: the setpoint comes
  // to rest at the acceleration limit and stays there).
  void set_speed_percent(uint8_t percent);
  // Jump to a position at rest (start-up, home, loop off, loop re-enabled).
  void reset(int32_t position_q8);
  // One tick toward target_q8. Returns the new setpoint. (At rest on the target nothing
  // changes: checked inline, so a holding joint pays no call.)
  int32_t step(int32_t target_q8) {
    if (velocity_q8_ == 0 && target_q8 == setpoint_q8_) return setpoint_q8_;
    return step_moving(target_q8);
  }

  int32_t setpoint_q8() const { return setpoint_q8_; }
  int32_t velocity_q8() const { return velocity_q8_; }
  int32_t speed_limit_q8() const { return speed_limit_q8_; }
  int32_t accel_q8() const { return accel_q8_; }

 private:
  int32_t step_moving(int32_t target_q8);
  // Fastest speed toward the target that still stops within `distance` (see step()),
  // limited to [floor, ceiling): the caller needs it only inside that window.
  int16_t brake_speed_within(uint32_t distance, int16_t floor, int16_t ceiling) const;

  int32_t setpoint_q8_ = 0;
  uint32_t no_brake_distance_q8_ = 0;  // beyond this distance braking never limits speed
  uint32_t quarter_accel_sq_ = 0;      // a^2 / 4 (per configuration: no division per tick)
  int16_t velocity_q8_ = 0;
  int16_t speed_limit_q8_ = 0;
  int16_t accel_q8_ = 1;
  uint16_t half_accel_q8_ = 0;   // a / 2
  uint16_t twice_accel_q8_ = 2;  // 2 a
  // top speed = 100 x top_per_percent_ + top_remainder_ (set_speed without a division)
  uint8_t top_per_percent_ = 0;
  uint8_t top_remainder_ = 0;
};

}  // namespace joint_bus
}  // namespace armctl
