#include "portable/setpoint_ramp.hpp"

#include "portable/fixed_point.hpp"

namespace armctl {
namespace joint_bus {

namespace {
const int32_t kTopSpeedMaxQ8 = INT32_C(51200);  // 200 clicks/tick: top^2 fits in uint32
const int32_t kAccelMaxQ8 = INT32_C(5120);      // 20,000,000 clicks/s^2
}  // namespace

void SetpointRamp::configure(int32_t top_speed_q8, int32_t accel_q8) {
  top_speed_q8_ = clamp32(top_speed_q8, 0, kTopSpeedMaxQ8);
  accel_q8_ = clamp32(accel_q8, 1, kAccelMaxQ8);
  // Beyond this distance even the top speed can brake in time, so braking is ignored
  // (and 2*a*E below never has to be computed for large E, keeping it inside uint32).
  const uint32_t top = static_cast<uint32_t>(top_speed_q8_);
  const uint32_t ua = static_cast<uint32_t>(accel_q8_);
  no_brake_distance_q8_ = top * top / (2u * ua) + 1u;
  half_accel_q8_ = static_cast<uint16_t>(ua / 2u);
  twice_accel_q8_ = static_cast<uint16_t>(ua * 2u);
  quarter_accel_sq_ = ua * ua / 4u;
  top_per_percent_ = static_cast<uint16_t>(top / 100u);
  top_remainder_ = static_cast<uint8_t>(top % 100u);
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
  speed_limit_q8_ = static_cast<int32_t>(static_cast<uint32_t>(top_per_percent_) * percent) +
                    small_quotient;
}

void SetpointRamp::reset(int32_t position_q8) {
  setpoint_q8_ = position_q8;
  velocity_q8_ = 0;
}

// The brake speed is b = max(0, r - a/2) with r = floor(sqrt(Q)), Q = a^2/4 + 2*a*distance:
// u + (u-a) + (u-2a) + ... <= distance  <=>  u <= sqrt(a^2/4 + 2*a*distance) - a/2.
// Returns max(b, floor) if b < ceiling, else ceiling (0 <= floor < ceiling). Instead of a
// full 16-step square root it compares Q with squares (16 x 16 bit products, cheap on the
// AVR) and, only when b falls strictly inside the window, bisects it: at most log2(2a)
// steps, and none while cruising or braking by exactly a per tick.
int32_t SetpointRamp::brake_speed_within(uint32_t distance, int32_t floor, int32_t ceiling) const {
  const uint32_t q = quarter_accel_sq_ + static_cast<uint32_t>(twice_accel_q8_) * distance;
  // Window bounds + a/2 stay below 51200 + 2 * 2560 + 1: they fit uint16, squares uint32.
  uint16_t high = static_cast<uint16_t>(ceiling + half_accel_q8_);  // r < high?
  if (static_cast<uint32_t>(high) * high <= q) return ceiling;
  uint16_t low = static_cast<uint16_t>(floor + half_accel_q8_ + 1);  // r >= low?
  if (static_cast<uint32_t>(low) * low > q) return floor;
  // Now low <= r < high: bisect for the largest r with r^2 <= q.
  while (static_cast<uint16_t>(high - low) > 1u) {
    const uint16_t mid = static_cast<uint16_t>(low + ((high - low) >> 1));
    if (static_cast<uint32_t>(mid) * mid <= q) {
      low = mid;
    } else {
      high = mid;
    }
  }
  return static_cast<int32_t>(low) - half_accel_q8_;
}

int32_t SetpointRamp::step_moving(int32_t target_q8) {
  const int32_t error = target_q8 - setpoint_q8_;
  const bool backward = error < 0;
  const uint32_t distance = abs32(error);
  const int32_t toward = with_sign(velocity_q8_, backward);  // < 0: moving away
  const int32_t a = accel_q8_;

  // The speed toward the target changes by at most a per tick, toward
  // wanted = min(speed limit, brake speed):  next = clamp(wanted, toward - a, toward + a)
  //                                              = min(clamp(limit), clamp(brake speed)).
  const int32_t lowest = toward - a;
  int32_t next = clamp32(speed_limit_q8_, lowest, toward + a);
  if (next > 0 && next > lowest && distance < no_brake_distance_q8_) {
    // The brake speed (>= 0) matters only where it lies below next.
    next = brake_speed_within(distance, lowest > 0 ? lowest : 0, next);
  }

  const int32_t landing = static_cast<int32_t>(distance);  // both ends within +-2^30: fits
  if (next >= 0 && landing <= next && landing <= a && landing - toward <= a &&
      toward - landing <= a) {
    // The target is reachable this tick with a speed change of at most `a`, and stopping
    // there next tick is another change of at most `a`: land exactly.
    setpoint_q8_ = target_q8;
    velocity_q8_ = 0;
  } else {
    velocity_q8_ = with_sign(next, backward);
    setpoint_q8_ += velocity_q8_;
  }
  return setpoint_q8_;
}

}  // namespace joint_bus
}  // namespace armctl
