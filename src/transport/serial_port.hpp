// A serial port (USB-serial adapter, UART, pty slave) as a ByteStream: termios raw 8N1,
// any standard baud rate (9600 by default), exclusive open, poll()-based reads.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "transport/fd_stream.hpp"

namespace armctl::transport {

constexpr std::uint32_t kDefaultBaud = 9600;

class SerialPort final : public FdStream {
 public:
  // Throws ArmctlError: io (naming the path and errno) if it cannot be opened or configured,
  // invalid_argument if `baud` is not a standard rate.
  static std::unique_ptr<SerialPort> open(const std::string& path,
                                          std::uint32_t baud = kDefaultBaud);
  ~SerialPort() override;
  std::uint32_t baud() const { return baud_; }
  // Discards bytes received but not yet read.
  void flush_input();

 private:
  SerialPort(int fd, std::string path, std::uint32_t baud);
  std::uint32_t baud_;
};

// The highest standard rate (the last of standard_bauds_text()).
inline constexpr std::uint32_t kMaxStandardBaud = 4000000;
// The termios speed constant for a standard rate, or nothing.
std::optional<unsigned> baud_constant(std::uint32_t baud);
// "50, 75, ..., 115200, ..., 4000000" for error messages.
std::string standard_bauds_text();

}  // namespace armctl::transport
