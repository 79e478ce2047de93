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
  no_brake_distance_q8_ = top * top / (2u * static_cast<uint32_t>(accel_q8_)) + 1u;
  set_speed_percent(100);
}

void SetpointRamp::set_speed_percent(uint8_t percent) {
  if (percent > 100) percent = 100;
  speed_limit_q8_ = top_speed_q8_ * static_cast<int32_t>(percent) / INT32_C(100);
}

void SetpointRamp::reset(int32_t position_q8) {
  setpoint_q8_ = position_q8;
  velocity_q8_ = 0;
}

int32_t SetpointRamp::step(int32_t target_q8) {
  const int32_t error = target_q8 - setpoint_q8_;
  if (error == 0 && velocity_q8_ == 0) return setpoint_q8_;
  const int32_t sign = error >= 0 ? 1 : -1;
  const uint32_t distance = abs32(error);
  const int32_t toward = sign * velocity_q8_;  // speed toward the target (< 0: moving away)
  const int32_t a = accel_q8_;

  // Fastest speed from which decelerating by `a` per tick stops within `distance`:
  // u + (u-a) + (u-2a) + ... <= distance  <=>  u <= sqrt(a^2/4 + 2*a*distance) - a/2.
  int32_t brake_speed = kTopSpeedMaxQ8;
  if (distance < no_brake_distance_q8_) {
    const uint32_t ua = static_cast<uint32_t>(a);
    const uint32_t root = isqrt32(ua * ua / 4u + 2u * ua * distance);
    brake_speed = static_cast<int32_t>(root) - a / 2;
    if (brake_speed < 0) brake_speed = 0;
  }
  const int32_t wanted = brake_speed < speed_limit_q8_ ? brake_speed : speed_limit_q8_;

  int32_t next;
  if (toward < wanted) {
    next = toward + a;
    if (next > wanted) next = wanted;
  } else {
    next = toward - a;
    if (next < wanted) next = wanted;
  }

  const int32_t landing = static_cast<int32_t>(distance);  // both ends within +-2^30: fits
  if (next >= 0 && landing <= next && landing <= a && landing - toward <= a &&
      toward - landing <= a) {
    // The target is reachable this tick with a speed change of at most `a`, and stopping
    // there next tick is another change of at most `a`: land exactly.
    setpoint_q8_ = target_q8;
    velocity_q8_ = 0;
  } else {
    velocity_q8_ = sign * next;
    setpoint_q8_ += velocity_q8_;
  }
  return setpoint_q8_;
}

}  // namespace joint_bus
}  // namespace armctl
