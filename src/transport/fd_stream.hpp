// A ByteStream over a POSIX file descriptor (tty, pty master, socket), waiting with poll()
// on the steady clock. SerialPort and Pty build on it.
#pragma once

#include <string>

#include "core/clock.hpp"
#include "transport/byte_stream.hpp"

namespace armctl::transport {

class FdStream : public ByteStream {
 public:
  // Takes ownership of `fd` (closed by the destructor). `name` appears in error messages.
  FdStream(int fd, std::string name);
  ~FdStream() override;
  FdStream(const FdStream&) = delete;
  FdStream& operator=(const FdStream&) = delete;

  void write(std::span<const std::uint8_t> bytes) override;
  std::size_t read(std::span<std::uint8_t> buffer, TimePoint deadline) override;
  const Clock& clock() const override { return clock_; }

  int fd() const { return fd_; }
  const std::string& name() const { return name_; }
  // Waits until everything written has left (tcdrain on ttys; no-op elsewhere).
  void drain();

 private:
  int fd_;
  std::string name_;
  SteadyClock clock_;
};

// "open /dev/ttyUSB0: Permission denied (errno 13)"
std::string errno_text(const std::string& what, const std::string& path, int err);

}  // namespace armctl::transport
