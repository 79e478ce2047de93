// The bus master's view of a joint bus: one shared UART plus one select line per joint.
// Implementations: the simulated bus (devices/joint_sim/sim_bus), a Linux serial port with
// GPIO select lines (serial_joint_bus_link), and a remote simulated arm (sim_link_client).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "core/clock.hpp"

namespace armctl::transport {

class JointBusLink {
 public:
  virtual ~JointBusLink() = default;

  // Select lines exist for joints 1..joint_count().
  virtual int joint_count() const = 0;
  virtual void set_select(int joint, bool high) = 0;

  // Queue bytes for the master's TX; flush() returns once they are all on the wire.
  virtual void write(std::span<const std::uint8_t> bytes) = 0;
  virtual void flush() = 0;

  // The next received byte, or nothing if none arrived before `deadline` (on clock()).
  // On simulated links waiting advances simulated time; nothing else ever does.
  virtual std::optional<std::uint8_t> read_byte(TimePoint deadline) = 0;

  // Discard every byte already received; returns how many were discarded.
  virtual std::size_t drain() = 0;

  virtual const Clock& clock() const = 0;
  virtual std::uint32_t baud() const = 0;
};

}  // namespace armctl::transport
