#include "portable_controller/ramp_model.hpp"

#include <math.h>

#include "portable/fixed_point.hpp"

namespace armctl {
namespace controller {

float ramp_accel(uint32_t cps2) {
  uint32_t q8 = joint_bus::accel_q8_per_tick2(cps2);
  if (q8 < 1) q8 = 1;  // as the joint's ramp takes it (portable/setpoint_ramp.cpp)
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

float ramp_speed(uint32_t cps, uint8_t percent) {
  const uint32_t top_q8 = joint_bus::speed_q8_per_tick(cps);
  return float(top_q8 * percent / 100u) * (1000.0f / 256.0f);
}

MotionPhases motion_phases(const SetpointMotion& m) {
  MotionPhases p{};
  p.x1 = m.x0;
  p.sign = 1.0f;
  if (m.v0 == 0.0f && m.x0 == m.target) return p;  // at rest on its target
  const float a = m.accel;
  const float per_a = 1.0f / a;  // one division: the AVR divides slowly
  float d = m.target - m.x0;
  p.sign = d < 0.0f ? -1.0f : 1.0f;
  p.distance = d * p.sign;
  p.u1 = m.v0 * p.sign;
  if (p.u1 < 0.0f || p.u1 * p.u1 > 2.0f * a * p.distance) {
    // Moving away, or too fast to stop before the target: to rest first (past it), then back.
    const float speed = p.u1 < 0.0f ? -p.u1 : p.u1;
    p.brake_s = speed * per_a;
    p.x1 = m.x0 + m.v0 * speed * per_a / 2.0f;
    p.u1 = 0.0f;
    d = m.target - p.x1;
    p.sign = d < 0.0f ? -1.0f : 1.0f;
    p.distance = d * p.sign;
  }
  const float u = p.u1;
  if (u > m.limit) {
    p.peak = m.limit;  // slowing to the new limit (0: held short)
  } else {
    const float triangle = sqrtf(a * p.distance + u * u / 2.0f);
    p.peak = triangle < m.limit ? triangle : m.limit;
  }
  p.change_s = (p.peak > u ? p.peak - u : u - p.peak) * per_a;
  p.stop_s = p.peak * per_a;
  if (p.peak > 0.0f) {
    const float changing = (p.peak > u ? p.peak * p.peak - u * u : u * u - p.peak * p.peak) * per_a / 2.0f;
    const float cruise = p.distance - changing - p.peak * p.stop_s / 2.0f;
    p.cruise_s = cruise > 0.0f ? cruise / p.peak : 0.0f;
  }
  return p;
}

SetpointState motion_at(const SetpointMotion& m, const MotionPhases& p, float t) {
  const float a = m.accel;
  if (t < 0.0f) t = 0.0f;
  if (t < p.brake_s) {
    const float slowing = m.v0 < 0.0f ? a : -a;
    return SetpointState{m.x0 + m.v0 * t + slowing * t * t / 2.0f, m.v0 + slowing * t};
  }
  t -= p.brake_s;
  const float u = p.u1, s = p.sign;
  const float change = p.peak > u ? a : -a;
  if (t < p.change_s) return SetpointState{p.x1 + s * (u * t + change * t * t / 2.0f), s * (u + change * t)};
  float x = p.x1 + s * (u + p.peak) * p.change_s / 2.0f;
  t -= p.change_s;
  if (t < p.cruise_s) return SetpointState{x + s * p.peak * t, s * p.peak};
  x += s * p.peak * p.cruise_s;
  t -= p.cruise_s;
  if (p.peak > 0.0f && t < p.stop_s) return SetpointState{x + s * (p.peak * t - a * t * t / 2.0f), s * (p.peak - a * t)};
  if (p.peak > 0.0f || p.distance == 0.0f) return SetpointState{m.target, 0.0f};
  return SetpointState{x, 0.0f};  // held short
}

float motion_arrival_s(const MotionPhases& p) {
  if (p.peak <= 0.0f && p.distance > 0.5f) return -1.0f;
  return p.brake_s + p.change_s + p.cruise_s + p.stop_s;
}

float limit_for_arrival(const SetpointMotion& m, const MotionPhases& fast, float time_s, float top) {
  const float a = m.accel;
  const float t = time_s - fast.brake_s;  // for the phases toward the target
  const float u = fast.u1, d = fast.distance;
  if (t <= 0.0f || d <= 0.0f) return top;
  // Speeding up to L (>= u), cruising, braking: t = (L - u)/a + d/L + u^2/(2 a L), i.e.
  // L^2 - (u + a t) L + a d + u^2/2 = 0, the smaller root.
  const float b = u + a * t;
  const float discriminant = b * b - 4.0f * (a * d + u * u / 2.0f);
  if (discriminant < 0.0f) return top;
  float limit = (b - sqrtf(discriminant)) / 2.0f;
  if (limit < u) {
    // Slowing down to L (< u): t = u/a + (d - u^2/(2a)) / L.
    const float rest = t - u / a;
    const float left = d - u * u / (2.0f * a);
    if (rest <= 0.0f) return top;
    limit = left > 0.0f ? left / rest : 0.0f;
  }
  return limit > top ? top : limit;
}

}  // namespace controller
}  // namespace armctl
