// Small helpers shared by the portable controller files: time comparisons on the wrapping
// microsecond clock, and saturating counters.
#pragma once

#include <stdint.h>

namespace armctl {
namespace controller {

// `now` is at or past `at` (both from a wrapping 32-bit microsecond counter; valid while
// they are less than 35 minutes apart).
inline bool reached(uint32_t now, uint32_t at) { return static_cast<int32_t>(now - at) >= 0; }

inline void count_up(uint16_t& counter) {
  if (counter != 0xFFFFu) ++counter;
}

}  // namespace controller
}  // namespace armctl
