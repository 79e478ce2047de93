#include "portable/fault_monitor.hpp"

#include "portable/joint_bus_codes.hpp"

namespace armctl {
namespace joint_bus {

int16_t FaultMonitor::tick(int32_t error_q8, uint16_t count16, int16_t duty) {
  // The rest is 16-bit on purpose (flash and cycles on the AVR): the error magnitude
  // saturates at 32767 clicks, far beyond both limits, and the motion of one run is taken
  // from the low 16 bits of the count, exact for runs under 32768 clicks (0.1 s at the
  // fastest accepted speed is 5,000).
  const bool positive = error_q8 > 0;
  int32_t wide = (positive ? error_q8 : -error_q8) >> 8;
  if (wide > 32767) wide = 32767;
  const int16_t magnitude = static_cast<int16_t>(wide);
  int16_t faults = 0;

  if (magnitude > following_limit_clicks) {
    if (++follow_ticks_ >= following_ticks) faults |= fault_following_error;
  } else {
    follow_ticks_ = 0;
  }

  const bool drives_with_error = duty != 0 && magnitude != 0 && ((duty > 0) == positive);
  if (!drives_with_error || !run_active_ || magnitude < run_max_error_) {
    // (Re)start a run here: the loop pushes toward the setpoint and we watch what follows.
    run_active_ = drives_with_error;
    run_ticks_ = 0;
    run_half_count_ = count16;
    run_half_against_ = no_half;
    run_max_error_ = magnitude;
    return faults;
  }
  run_max_error_ = magnitude;
  if (++run_ticks_ < runaway_ticks / 2) return faults;
  // A half is complete: how far the joint moved against the drive in it, and in the one before
  // (never more than a few thousand clicks in 50 ms, so the sum stays far inside 16 bits).
  int16_t against = static_cast<int16_t>(count16 - run_half_count_);
  if (duty > 0) against = static_cast<int16_t>(-against);
  if (against >= run_half_against_ && against + run_half_against_ >= runaway_min_clicks) faults |= fault_runaway;
  run_half_against_ = against;
  run_half_count_ = count16;
  run_ticks_ = 0;
  return faults;
}

}  // namespace joint_bus
}  // namespace armctl
