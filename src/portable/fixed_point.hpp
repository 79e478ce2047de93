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

}  // namespace joint_bus
}  // namespace armctl
