// A pseudo-terminal pair: the master side is a ByteStream for the program that plays the
// device (board emulator, fake joints); the slave path is opened like a serial port by
// the program under test. Both sides are raw (no echo, no line editing, 8-bit clean).
#pragma once

#include <memory>
#include <string>

#include "transport/fd_stream.hpp"

namespace armctl::transport {

class Pty {
 public:
  // Throws ArmctlError(io) naming the failing call and errno.
  static Pty open();

  // The device side. Reads and writes bytes the slave's user writes and reads.
  FdStream& master() { return *master_; }
  std::unique_ptr<FdStream> take_master() { return std::move(master_); }
  // e.g. /dev/pts/7: give it to SerialPort::open or `--device`.
  const std::string& slave_path() const { return slave_path_; }

  Pty(Pty&& other) noexcept;
  Pty& operator=(Pty&& other) noexcept;
  Pty(const Pty&) = delete;
  Pty& operator=(const Pty&) = delete;
  ~Pty();

 private:
  Pty() = default;
  std::unique_ptr<FdStream> master_;
  std::string slave_path_;
  int slave_keepalive_ = -1;  // keeps the slave open so the master never reads EIO/hangs up
};

}  // namespace armctl::transport
