#include "portable_controller/ramp_model.hpp"

#include <math.h>

namespace armctl {
namespace controller {

float ramp_accel(uint32_t cps2) {
  uint32_t q8 = (cps2 * 32u + 62500u) / 125000u;
  if (q8 < 1) q8 = 1;
  return float(q8) * (1e6f / 256.0f);
}

float shortest_time_s(float distance, float speed, float accel) {
  if (distance * accel >= speed * speed) return distance / speed + speed / accel;
  return 2.0f * sqrtf(distance / accel);
}

float ramp_covered(float t_s, float distance, float speed, float accel) {
  if (t_s <= 0.0f || distance <= 0.0f || speed <= 0.0f) return 0.0f;
  const float total_s = shortest_time_s(distance, speed, accel);
  if (t_s >= total_s) return distance;
  // Accelerating for `reach_s` (to the speed, or to the peak of a triangle), braking as
  // long at the end: before the half-way point of a triangle, or the cruise, a t^2 / 2.
  const float reach_s = distance * accel >= speed * speed ? speed / accel : total_s / 2.0f;
  if (t_s <= reach_s) return accel * t_s * t_s / 2.0f;
  const float left_s = total_s - t_s;
  if (left_s <= reach_s) return distance - accel * left_s * left_s / 2.0f;
  return speed * speed / (2.0f * accel) + speed * (t_s - reach_s);
}

}  // namespace controller
}  // namespace armctl
