// Time for the host side. Everything that waits takes a Clock, so tests and simulators
// run on deterministic simulated time and real hardware runs on the steady clock.
#pragma once

#include <chrono>
#include <cstdint>

namespace armctl {

using Duration = std::chrono::nanoseconds;
using TimePoint = std::chrono::time_point<std::chrono::steady_clock, Duration>;

class Clock {
 public:
  virtual ~Clock() = default;
  virtual TimePoint now() const = 0;
};

// The machine's monotonic clock: for real hardware and for long-lived simulators that run
// in step with the wall clock.
class SteadyClock final : public Clock {
 public:
  TimePoint now() const override {
    return std::chrono::time_point_cast<Duration>(std::chrono::steady_clock::now());
  }
};

// Simulated time: moves only when its owner advances it. Starts at zero.
class SimClock final : public Clock {
 public:
  TimePoint now() const override { return now_; }
  void advance(Duration d) { now_ += d; }
  void advance_to(TimePoint t) {
    if (t > now_) now_ = t;
  }

 private:
  TimePoint now_{};
};

// Time taken by `bytes` bytes of 8N1 (10 bit times each) at `baud`.
constexpr Duration wire_time(std::uint64_t bytes, std::uint32_t baud) {
  return Duration{static_cast<std::int64_t>(bytes * 10ULL * 1'000'000'000ULL / baud)};
}

}  // namespace armctl
