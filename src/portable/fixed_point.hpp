// Small integer helpers for the fixed-point loop code. int is 16 bits on the AVR, so every
// helper works on explicit int32_t/uint32_t.
#pragma once

#include <stdint.h>

namespace armctl {
namespace joint_bus {

inline int32_t clamp32(int32_t v, int32_t lo, int32_t hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

// clamp32 out of line, for start-up code (tuning and gains): one copy instead of one per
// use saves firmware flash; never used per tick.
int32_t clamp_setting(int32_t v, int32_t lo, int32_t hi);

inline uint32_t abs32(int32_t v) {
  return v < 0 ? static_cast<uint32_t>(0) - static_cast<uint32_t>(v) : static_cast<uint32_t>(v);
}

// Q16 -> integer, rounding half away from zero. Shifts of unsigned values only: no division
// (a 32-bit division is a ~600-cycle library call on the AVR) and no shift of a negative.
inline int32_t round_q16(int32_t v) {
  if (v >= 0) return static_cast<int32_t>((static_cast<uint32_t>(v) + UINT32_C(32768)) >> 16);
  return -static_cast<int32_t>((abs32(v) + UINT32_C(32768)) >> 16);
}

// The joint's speed and acceleration settings (clicks/s, clicks/s^2) in its ramp's units
// (Q8 clicks per 1 ms tick, per tick^2), rounded to nearest: * 256 / 1000 = * 32 / 125 and
// * 256 / 1e6 = * 32 / 125000, in unsigned arithmetic (the settings are positive, and the
// firmware then needs one division routine less). Far inside uint32 for every setting the
// joint accepts (portable/joint_tuning.hpp). Whatever models the joint's ramp (the host's
// motion model and sync plan, the Mega's ramp model) converts with these, as the joint does.
inline uint32_t speed_q8_per_tick(uint32_t cps) { return (cps * 32u + 62u) / 125u; }
inline uint32_t accel_q8_per_tick2(uint32_t cps2) { return (cps2 * 32u + 62500u) / UINT32_C(125000); }

}  // namespace joint_bus
}  // namespace armctl
