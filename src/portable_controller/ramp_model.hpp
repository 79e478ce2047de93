// The joints' setpoint ramp seen from the controller (portable/setpoint_ramp.hpp runs it
// on each joint, one 1 ms tick at a time): a trapezoid, accelerating at a to the speed
// limit, cruising, braking to rest on the target. Closed forms in floating point, for the
// main loop only (never an interrupt handler).
#pragma once

#include <stdint.h>

namespace armctl {
namespace controller {

// The acceleration a joint's setpoint ramp really runs: Q8 clicks per tick^2 =
// (cps2 * 32 + 62500) / 125000, at least 1; 40,000 clicks/s^2 is 39,062, 15,000 is 15,625.
// Planning with the configured figure would misjudge every ramp.
float ramp_accel(uint32_t cps2);

// Seconds a joint at rest needs for `distance` clicks at `speed` and `accel`.
float shortest_time_s(float distance, float speed, float accel);

// One rest-to-rest ramp, its divisions and square root done once (when a move is
// planned), so that where it stands at an instant costs a few multiplications: the
// controller evaluates it on every poll of a moving joint, between two transactions.
struct RampShape {
  float distance;    // clicks
  float speed;       // clicks/s
  float half_accel;  // clicks/s^2 / 2
  float reach_s;     // accelerating (and braking) this long
  float total_s;     // at rest on the target from then on
};
RampShape ramp_shape(float distance, float speed, float accel);

// Clicks the setpoint has covered `t_s` seconds after its drive took effect. With the
// slower of a move's speeds this is a lower bound of where the setpoint is (the
// controller's stall check, ControllerCore::check_ramp).
float ramp_covered(const RampShape& ramp, float t_s);

}  // namespace controller
}  // namespace armctl
