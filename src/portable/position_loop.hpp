// The joint's position loop: target, zone, on/off, setpoint ramp and PID, run once per
// 1 ms tick with the encoder count. Implements the loop side of the joint bus commands
// exactly as spec/joint-bus.md decides (loop off lets target follow position; re-enabling
// does not jump; home keeps on/off and clears integral and setpoint).
#pragma once

#include <stdint.h>

#include "portable/joint_tuning.hpp"
#include "portable/pid_controller.hpp"
#include "portable/setpoint_ramp.hpp"

namespace armctl {
namespace joint_bus {

// Clamp a 32-bit click count to what a bus word can carry.
inline int16_t saturate_to_int16(int32_t v) {
  if (v > 32767) return 32767;
  if (v < -32768) return -32768;
  return static_cast<int16_t>(v);
}

class PositionLoop {
 public:
  // Clamps the tuning into its documented ranges, loop on, speed 100 %, zone 0, target and
  // setpoint at `count`.
  void begin(const JointTuning& tuning, int32_t count);
  // One 1 ms tick with the current encoder count.
  DriveOutput tick(int32_t count);

  // Command side (each is atomic; the caller validated the data).
  void set_enabled(bool on, int32_t count);
  void home();  // the caller sets the encoder count to 0 at the same time
  // Bridge off while a fault is held: target follows the position like a loop that is off,
  // so clearing the fault holds the joint where it then is.
  void hold(int32_t count) { sync_to(count); }
  void set_target(int16_t target) { target_ = target; }
  void set_speed_percent(uint8_t percent) { speed_percent_ = percent; ramp_.set_speed_percent(percent); }
  void set_zone(int16_t zone) { zone_ = zone; }

  bool enabled() const { return enabled_; }
  int16_t target() const { return target_; }
  uint8_t speed_percent() const { return speed_percent_; }
  int16_t zone() const { return zone_; }
  bool target_reached(int32_t count) const;
  // Setpoint - position of the last running tick, Q8 clicks (for the fault monitor).
  int32_t error_q8() const { return error_q8_; }
  const SetpointRamp& ramp() const { return ramp_; }
  const PidController& pid() const { return pid_; }
  const JointTuning& tuning() const { return tuning_; }

 private:
  void sync_to(int32_t count);  // target := position, setpoint at rest there, PID cleared

  JointTuning tuning_ = JointTuning();
  SetpointRamp ramp_;
  PidController pid_;
  int32_t error_q8_ = 0;
  int16_t target_ = 0;
  int16_t zone_ = 0;
  uint8_t speed_percent_ = 100;
  bool enabled_ = true;
};

}  // namespace joint_bus
}  // namespace armctl
