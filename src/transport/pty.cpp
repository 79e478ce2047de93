#include "transport/pty.hpp"

#include <cerrno>
#include <cstdlib>
#include <utility>

#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include "core/error.hpp"

namespace armctl::transport {

Pty Pty::open() {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (master < 0) throw ArmctlError(ErrorKind::io, errno_text("posix_openpt", "/dev/ptmx", errno));
  auto fail = [&](const char* what) {
    const int err = errno;
    ::close(master);
    throw ArmctlError(ErrorKind::io, errno_text(what, "pty master", err));
  };
  if (::grantpt(master) != 0) fail("grantpt");
  if (::unlockpt(master) != 0) fail("unlockpt");
  char name[128];
  if (::ptsname_r(master, name, sizeof name) != 0) fail("ptsname");

  // Raw mode on the slave so the line discipline passes every byte (0x0D, 0x11, ...) as is.
  const int slave = ::open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (slave < 0) fail("open pty slave");
  termios tio{};
  if (::tcgetattr(slave, &tio) == 0) {
    ::cfmakeraw(&tio);
    ::tcsetattr(slave, TCSANOW, &tio);
  }
  Pty p;
  p.master_ = std::make_unique<FdStream>(master, "pty master of " + std::string(name));
  p.slave_path_ = name;
  p.slave_keepalive_ = slave;
  return p;
}

Pty::Pty(Pty&& other) noexcept
    : master_(std::move(other.master_)),
      slave_path_(std::move(other.slave_path_)),
      slave_keepalive_(std::exchange(other.slave_keepalive_, -1)) {}

Pty& Pty::operator=(Pty&& other) noexcept {
  if (this != &other) {
    if (slave_keepalive_ >= 0) ::close(slave_keepalive_);
    master_ = std::move(other.master_);
    slave_path_ = std::move(other.slave_path_);
    slave_keepalive_ = std::exchange(other.slave_keepalive_, -1);
  }
  return *this;
}

Pty::~Pty() {
  if (slave_keepalive_ >= 0) ::close(slave_keepalive_);
}

}  // namespace armctl::transport
