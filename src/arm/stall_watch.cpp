#include "arm/stall_watch.hpp"

#include <cmath>

namespace armctl::arm {

StallWatch::StallWatch(std::vector<StallThresholds> joints, Duration time)
    : limits_(std::move(joints)), time_(time), joints_(limits_.size()) {}

std::optional<JointStall> StallWatch::read(TimePoint now, std::span<const double> positions,
                                           std::span<const std::optional<double>> driven_to) {
  if (time_ <= Duration{0}) return std::nullopt;
  for (std::size_t i = 0; i < joints_.size() && i < positions.size(); ++i) {
    Joint& j = joints_[i];
    const StallThresholds& limit = limits_[i];
    const std::optional<double> to = i < driven_to.size() ? driven_to[i] : std::nullopt;
    if (limit.driven <= 0 || !to || std::abs(*to - positions[i]) <= limit.driven) {
      j.standing = false;  // not driven (there, or left alone): nothing to stall
      continue;
    }
    if (!j.standing || std::abs(positions[i] - j.at) > limit.moves) {
      // Driven, and just began to stand still (or moved since): the time counts from here.
      j = Joint{true, now, positions[i]};
      continue;
    }
    if (now - j.since >= time_)
      return JointStall{int(i), {}, positions[i], *to, std::chrono::duration<double>(now - j.since).count()};
  }
  return std::nullopt;
}

}  // namespace armctl::arm
