// A bidirectional byte pipe (serial port, pty, socket, in-memory). Robot Commands links
// build on it; USB HID, which moves whole reports, has its own link type.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "core/clock.hpp"

namespace armctl::transport {

class ByteStream {
 public:
  virtual ~ByteStream() = default;
  // Writes all bytes or throws ArmctlError: io, or timeout when the peer stops taking bytes
  // (every implementation bounds the wait).
  virtual void write(std::span<const std::uint8_t> bytes) = 0;
  // Reads what is available (at least one byte) or waits until `deadline`; 0 = timed out.
  virtual std::size_t read(std::span<std::uint8_t> buffer, TimePoint deadline) = 0;
  virtual const Clock& clock() const = 0;
};

}  // namespace armctl::transport
