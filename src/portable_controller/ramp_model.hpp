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

// The velocity a joint's ramp holds at set_speed `percent`, as its fixed-point ramp
// quantizes it: Q8 clicks per tick, (cps * 32 + 62) / 125 at 100 %, x percent / 100.
float ramp_speed(uint32_t cps, uint8_t percent);

// A joint's setpoint in motion, as its ramp runs it in continuous time: from `x0` at
// velocity `v0` (signed) toward `target`, under the speed limit `limit` (>= 0) and the
// acceleration `accel`. The ramp brakes to rest first if it moves away from the target or
// cannot stop before it (it then comes back), then changes speed to the limit (or to the
// peak that lets it stop in time), cruises and brakes onto the target. With limit 0 it
// comes to rest where it is (held short, as GroupStop's set_speed 0 leaves it). Floating
// point, for the main loop's planning pass only (ControllerCore::plan_move).
struct SetpointMotion {
  float x0;      // clicks
  float v0;      // clicks/s
  float target;  // clicks
  float limit;   // clicks/s
  float accel;   // clicks/s^2
};
struct SetpointState {
  float x;  // clicks
  float v;  // clicks/s, signed
};
// A SetpointMotion cut into its phases (one square root and one division), so that where it
// is at an instant costs a few multiplications: an optional brake to rest (moving away, or
// unable to stop before the target), then toward the target (`sign`): from speed `u1` to
// `peak`, cruising, braking to rest.
struct MotionPhases {
  float brake_s;   // braking to rest first
  float x1;        // where the phases toward the target begin
  float sign;      // +1 / -1: toward the target from x1
  float distance;  // from x1 to the target
  float u1;        // speed toward the target at x1 (>= 0)
  float peak;      // cruise speed (0: it only comes to rest)
  float change_s;  // u1 -> peak
  float cruise_s;
  float stop_s;    // peak -> 0
};
MotionPhases motion_phases(const SetpointMotion& m);
SetpointState motion_at(const SetpointMotion& m, const MotionPhases& p, float t_s);
// Seconds until it is at rest on its target; negative if never (limit 0, short of it).
float motion_arrival_s(const MotionPhases& p);
// The smallest speed limit (clicks/s, at most `top`) that brings it to rest on its target
// no sooner than `time_s` from now, by the same phases; `top` if even `top` is late.
// `fast`: its phases with the limit `top`.
float limit_for_arrival(const SetpointMotion& m, const MotionPhases& fast, float time_s, float top);

// The same, its phases made on the way (tests).
inline SetpointState motion_at(const SetpointMotion& m, float t_s) { return motion_at(m, motion_phases(m), t_s); }
inline float motion_arrival_s(const SetpointMotion& m) { return motion_arrival_s(motion_phases(m)); }
inline float limit_for_arrival(const SetpointMotion& m, float time_s, float top) {
  SetpointMotion fast = m;
  fast.limit = top;
  return limit_for_arrival(m, motion_phases(fast), time_s, top);
}

}  // namespace controller
}  // namespace armctl
