#include "portable/setpoint_ramp.hpp"

#include "portable/fixed_point.hpp"

namespace armctl {
namespace joint_bus {

void SetpointRamp::configure(int32_t top_speed_q8, int32_t accel_q8) {
  const uint16_t top = static_cast<uint16_t>(clamp_setting(top_speed_q8, 0, top_speed_max_q8));
  const uint16_t a = static_cast<uint16_t>(clamp_setting(accel_q8, 1, accel_max_q8));
  accel_q8_ = static_cast<int16_t>(a);
  // Beyond this distance even the top speed can brake in time, so braking is ignored
  // (and 2*a*distance below is only computed for distances that keep it inside uint32).
  no_brake_distance_q8_ = static_cast<uint32_t>(top) * top / (2u * a) + 1u;
  half_accel_q8_ = static_cast<uint16_t>(a / 2u);
  twice_accel_q8_ = static_cast<uint16_t>(a * 2u);
  quarter_accel_sq_ = static_cast<uint32_t>(a) * a / 4u;
  // In 32 bits on purpose: the firmware then needs only the 32-bit division routine.
  const uint32_t top32 = top;
  top_per_percent_ = static_cast<uint8_t>(top32 / 100u);
  top_remainder_ = static_cast<uint8_t>(top32 - 100u * top_per_percent_);
  set_speed_percent(100);
}

void SetpointRamp::set_speed_percent(uint8_t percent) {
  if (percent > 100) percent = 100;
  // top x percent / 100 = per_percent x percent + remainder x percent / 100, exactly; the
  // last quotient (< 10000 / 100) is (x * 5243) >> 19, exact for x < 43699: no division,
  // because set_speed runs in the bus path with interrupts masked.
  const uint16_t small = static_cast<uint16_t>(top_remainder_ * percent);
  const uint16_t small_quotient =
      static_cast<uint16_t>((static_cast<uint32_t>(small) * UINT32_C(5243)) >> 19);
  speed_limit_q8_ = static_cast<int16_t>(static_cast<uint16_t>(top_per_percent_ * percent) +
                                         small_quotient);
}

void SetpointRamp::reset(int32_t position_q8) {
  setpoint_q8_ = position_q8;
  velocity_q8_ = 0;
}

// The brake speed is b = max(0, r - a/2) with r = floor(sqrt(Q)), Q = a^2/4 + 2*a*distance:
// u + (u-a) + (u-2a) + ... <= distance  <=>  u <= sqrt(a^2/4 + 2*a*distance) - a/2.
// Returns max(b, floor) if b < ceiling, else ceiling (0 <= floor < ceiling). Instead of a
// full 16-step square root it compares Q with squares (16 x 16 bit products, cheap on the
// AVR) and, only when b falls strictly inside the window, bisects it: at most
// log2((2a + 1) / 4) steps (7 at the acceleration bound), none while cruising.
int16_t SetpointRamp::brake_speed_within(uint32_t distance, int16_t floor, int16_t ceiling) const {
  const uint32_t q = quarter_accel_sq_ + static_cast<uint32_t>(twice_accel_q8_) * distance;
  // Window bounds + a/2 stay below 12800 + 2 * 256 + 1: they fit uint16, squares uint32.
  uint16_t high = static_cast<uint16_t>(ceiling + half_accel_q8_);  // r < high?
  if (static_cast<uint32_t>(high) * high <= q) return ceiling;
  uint16_t low = static_cast<uint16_t>(floor + half_accel_q8_ + 1);  // r >= low?
  if (static_cast<uint32_t>(low) * low > q) return floor;
  // Now low <= r < high: bisect for the largest r with r^2 <= q, to within 4 Q8 units
  // (1/64 click/tick, 16 clicks/s): low only moves to values with low^2 <= q, so the result
  // never exceeds the brake speed (braking may start that little bit early, never late),
  // and two bisection steps fewer bound the worst-case tick.
  while (static_cast<uint16_t>(high - low) > 4u) {
    const uint16_t mid = static_cast<uint16_t>(low + ((high - low) >> 1));
    if (static_cast<uint32_t>(mid) * mid <= q) {
      low = mid;
    } else {
      high = mid;
    }
  }
  return static_cast<int16_t>(low - half_accel_q8_);
}

int32_t SetpointRamp::step_moving(int32_t target_q8) {
  const int32_t error = target_q8 - setpoint_q8_;
  const bool backward = error < 0;
  const uint32_t distance = abs32(error);
  const int16_t a = accel_q8_;
  // Speed toward the target (< 0: moving away). All speeds here are within
  // +-(12800 + 512): 16-bit arithmetic.
  const int16_t toward = backward ? static_cast<int16_t>(-velocity_q8_) : velocity_q8_;

  // The speed toward the target changes by at most a per tick, toward
  // wanted = min(speed limit, brake speed):  next = clamp(wanted, toward - a, toward + a)
  //                                              = min(clamp(limit), clamp(brake speed)).
  const int16_t lowest = static_cast<int16_t>(toward - a);
  const int16_t highest = static_cast<int16_t>(toward + a);
  int16_t next = speed_limit_q8_;
  if (next > highest) next = highest;
  if (next < lowest) next = lowest;
  if (next > 0 && next > lowest && distance < no_brake_distance_q8_) {
    // The brake speed (>= 0) matters only where it lies below next.
    next = brake_speed_within(distance, lowest > 0 ? lowest : 0, next);
  }

  if (next >= 0 && distance <= static_cast<uint16_t>(a)) {
    const int16_t landing = static_cast<int16_t>(distance);
    if (landing <= next && landing - toward <= a && toward - landing <= a) {
      // The target is reachable this tick with a speed change of at most `a`, and stopping
      // there next tick is another change of at most `a`: land exactly.
      setpoint_q8_ = target_q8;
      velocity_q8_ = 0;
      return setpoint_q8_;
    }
  }
  velocity_q8_ = backward ? static_cast<int16_t>(-next) : next;
  setpoint_q8_ += velocity_q8_;
  return setpoint_q8_;
}

}  // namespace joint_bus
}  // namespace armctl
