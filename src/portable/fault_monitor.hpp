// Watches the position loop for the two faults a joint must stop on by itself (the bridge
// goes off and stays off until clear_faults; docs/joint-controller.md "Faults"):
//   runaway          the loop drives toward its setpoint but the joint moves the other way,
//                    and not slower and slower: for runaway_ticks in a row the error never
//                    shrank, the drive kept the error's sign, the joint moved at least
//                    runaway_min_clicks against the drive, and no less in the second half of
//                    that time than in the first. That is a motor wired with the other
//                    polarity (it speeds up away from the setpoint) or a load stronger than
//                    the bridge (it keeps its speed). Braking through an overshoot also moves
//                    against the drive, for a heavy joint longer than runaway_ticks, but it
//                    slows down (the default tuning on the SCARA's SHOULDER brakes for ~200 ms).
//   following_error  |setpoint - position| above following_limit_clicks for
//                    following_ticks in a row: a stalled or blocked joint, a dead bridge.
// Integer only, a few 32-bit compares per tick (it runs inside the 1 ms control step).
#pragma once

#include <stdint.h>

namespace armctl {
namespace joint_bus {

class FaultMonitor {
 public:
  static const uint16_t runaway_ticks = 100;        // 100 ms at the 1 kHz tick
  static const int16_t runaway_min_clicks = 64;     // moved against the drive over that time
  static const int16_t following_limit_clicks = 4096;
  static const uint16_t following_ticks = 500;      // 500 ms

  // Forget the history (loop off, fault cleared, home): the next tick starts afresh.
  void reset() {
    run_ticks_ = 0;
    follow_ticks_ = 0;
    run_active_ = false;
  }
  // One tick of a running loop: setpoint - position (Q8 clicks, within +-2^30), the encoder
  // count (its low 16 bits are enough) and the duty the loop asked for (before polarity:
  // > 0 means "count up"). Returns the fault bits to raise.
  int16_t tick(int32_t error_q8, uint16_t count, int16_t duty);

 private:
  // The run is watched in halves of runaway_ticks / 2: the low 16 bits of the count where the
  // current half began, and how far the joint moved against the drive in the half before
  // (no_half before a whole one).
  static const int16_t no_half = 32767;
  uint16_t run_half_count_ = 0;
  int16_t run_half_against_ = no_half;
  int16_t run_max_error_ = 0;
  uint8_t run_ticks_ = 0;  // in the current half
  uint16_t follow_ticks_ = 0;
  bool run_active_ = false;
};

}  // namespace joint_bus
}  // namespace armctl
