// Bus-servo position units: 0..1000 span 240 degrees, 500 = centre (spec "Units").
#pragma once

#include <cmath>
#include <cstdint>

namespace armctl::rc {

constexpr double kDegreesSpan = 240.0;
constexpr double kPositionsPerDegree = 1000.0 / kDegreesSpan;

// Degrees from centre (-120..+120 for 0..1000).
constexpr double position_to_degrees(double position) {
  return (position - 500.0) / kPositionsPerDegree;
}

// Nearest position for an angle from centre; not clamped (callers check 0..1000).
inline long degrees_to_position(double degrees) {
  return std::lround(500.0 + degrees * kPositionsPerDegree);
}

}  // namespace armctl::rc
