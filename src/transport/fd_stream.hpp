// A ByteStream over a POSIX file descriptor (tty, pty master, socket, pipe), waiting with
// poll() on the steady clock. SerialPort and Pty build on it. No call waits without a
// deadline: reads take one, and a write gives up after write_timeout() when the peer stops
// taking bytes (a full pty or pipe buffer, a serial port stuck in flow control).
#pragma once

#include <string>

#include "core/clock.hpp"
#include "transport/byte_stream.hpp"

namespace armctl::transport {

class FdStream : public ByteStream {
 public:
  // Takes ownership of `fd` (closed by the destructor) and makes it non-blocking, so that
  // no write can block past its deadline. `name` appears in error messages.
  FdStream(int fd, std::string name);
  ~FdStream() override;
  FdStream(const FdStream&) = delete;
  FdStream& operator=(const FdStream&) = delete;

  // Writes all bytes, or throws ArmctlError: timeout if they are not all taken within
  // write_timeout() (saying how many were), io if the OS refuses.
  void write(std::span<const std::uint8_t> bytes) override;
  std::size_t read(std::span<std::uint8_t> buffer, TimePoint deadline) override;
  const Clock& clock() const override { return clock_; }

  int fd() const { return fd_; }
  Duration write_timeout() const { return write_timeout_; }
  void set_write_timeout(Duration timeout) { write_timeout_ = timeout; }
  const std::string& name() const { return name_; }
  // Waits until everything written has left (tcdrain on ttys; no-op elsewhere).
  void drain();

 private:
  int fd_;
  std::string name_;
  SteadyClock clock_;
  // Longer than any frame either protocol sends takes on the wire at 9600 baud (~0.1 s),
  // short enough that a host notices a peer that stopped reading.
  Duration write_timeout_ = std::chrono::seconds(2);
};

// "open /dev/ttyUSB0: Permission denied (errno 13)"
std::string errno_text(const std::string& what, const std::string& path, int err);

}  // namespace armctl::transport
