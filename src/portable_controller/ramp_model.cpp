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

RampShape ramp_shape(float distance, float speed, float accel) {
  RampShape r{distance, speed, accel / 2.0f, 0.0f, 0.0f};
  if (distance <= 0.0f || speed <= 0.0f) return r;
  r.total_s = shortest_time_s(distance, speed, accel);
  // A trapezoid accelerates until it cruises; a triangle until half-way.
  r.reach_s = distance * accel >= speed * speed ? speed / accel : r.total_s / 2.0f;
  return r;
}

float ramp_covered(const RampShape& r, float t_s) {
  if (t_s <= 0.0f) return 0.0f;
  if (t_s >= r.total_s) return r.distance;
  if (t_s <= r.reach_s) return r.half_accel * t_s * t_s;
  const float left_s = r.total_s - t_s;
  if (left_s <= r.reach_s) return r.distance - r.half_accel * left_s * left_s;
  return r.half_accel * r.reach_s * r.reach_s + r.speed * (t_s - r.reach_s);
}

}  // namespace controller
}  // namespace armctl
