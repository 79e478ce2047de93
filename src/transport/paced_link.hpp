// Runs a simulated joint bus (SimBus: simulated time that moves only while the master
// waits) in step with the wall clock, so that a controller serving a real host over a pty
// sees an arm that moves in real time. After every call that lets simulated time pass,
// sleeps until the wall clock has caught up. If the simulation falls behind (a slow or
// loaded machine), it runs as fast as it can and re-anchors instead of rushing to catch up.
#pragma once

#include <chrono>

#include "transport/joint_bus_link.hpp"

namespace armctl::transport {

class PacedLink final : public JointBusLink {
 public:
  explicit PacedLink(JointBusLink& simulated);

  int joint_count() const override { return inner_.joint_count(); }
  void set_select(int joint, bool high) override { inner_.set_select(joint, high); }
  void write(std::span<const std::uint8_t> bytes) override { inner_.write(bytes); }
  void flush() override;
  std::optional<std::uint8_t> read_byte(TimePoint deadline) override;
  std::size_t drain() override { return inner_.drain(); }
  const Clock& clock() const override { return inner_.clock(); }
  std::uint32_t baud() const override { return inner_.baud(); }

 private:
  void pace();

  JointBusLink& inner_;
  SteadyClock wall_;
  TimePoint sim_anchor_;
  TimePoint wall_anchor_;
};

// True if `link` runs on simulated time (its clock is a SimClock).
bool runs_on_simulated_time(const JointBusLink& link);

}  // namespace armctl::transport
