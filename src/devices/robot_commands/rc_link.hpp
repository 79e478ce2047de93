// A "Robot Commands link": moves whole frames between a host and one board. The SDK talks
// only to this, so serial ports, ptys, USB HID and in-memory/emulated boards behave the same.
#pragma once

#include <optional>
#include <string>

#include "core/clock.hpp"
#include "protocol/robot_commands/frame.hpp"

namespace armctl::robot_commands {

class RcLink {
 public:
  virtual ~RcLink() = default;
  // Sends one frame or throws ArmctlError(io).
  virtual void send(const rc::Frame& frame) = 0;
  // The next frame from the board, or nothing if none arrived before `deadline` (on
  // clock()). On simulated links waiting advances simulated time.
  virtual std::optional<rc::Frame> receive(TimePoint deadline) = 0;
  virtual const Clock& clock() const = 0;
  // "serial:/dev/ttyUSB0 at 9600 baud", "hid:/dev/hidraw3 (serial 4987...)": for errors.
  virtual std::string describe() const = 0;
  // How long a frame of `serial_bytes` bytes (its serial form) occupies the link: what
  // streaming is paced by. Serial links: 10 bit times per byte at their baud; the default
  // is the protocol's 9600 baud.
  virtual Duration frame_time(std::size_t serial_bytes) const { return wire_time(serial_bytes, 9600); }
  // Bytes/reports thrown away as unreadable so far (resynchronisation, bad reports).
  virtual std::size_t discarded() const { return 0; }
};

}  // namespace armctl::robot_commands
