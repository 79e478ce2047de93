#include "transport/serial_port.hpp"

#include <cerrno>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include "core/error.hpp"

namespace armctl::transport {
namespace {

struct BaudEntry {
  std::uint32_t rate;
  speed_t constant;
};

constexpr BaudEntry kBauds[] = {
    {50, B50},         {75, B75},         {110, B110},       {134, B134},
    {150, B150},       {200, B200},       {300, B300},       {600, B600},
    {1200, B1200},     {1800, B1800},     {2400, B2400},     {4800, B4800},
    {9600, B9600},     {19200, B19200},   {38400, B38400},   {57600, B57600},
    {115200, B115200}, {230400, B230400}, {460800, B460800}, {500000, B500000},
    {576000, B576000}, {921600, B921600}, {1000000, B1000000}, {1152000, B1152000},
    {1500000, B1500000}, {2000000, B2000000}, {2500000, B2500000}, {3000000, B3000000},
    {3500000, B3500000}, {4000000, B4000000},
};
static_assert(kBauds[std::size(kBauds) - 1].rate == kMaxStandardBaud, "kMaxStandardBaud is the last rate");

}  // namespace

std::optional<unsigned> baud_constant(std::uint32_t baud) {
  for (const auto& e : kBauds) {
    if (e.rate == baud) return e.constant;
  }
  return std::nullopt;
}

std::string standard_bauds_text() {
  std::string out;
  for (const auto& e : kBauds) {
    if (!out.empty()) out += ", ";
    out += std::to_string(e.rate);
  }
  return out;
}

std::unique_ptr<SerialPort> SerialPort::open(const std::string& path, std::uint32_t baud) {
  const auto speed = baud_constant(baud);
  if (!speed) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      "baud rate " + std::to_string(baud) + " for " + path +
                          " is not a standard rate (allowed: " + standard_bauds_text() + ")");
  }
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    std::string hint;
    if (err == EACCES) hint = " (is your user in the dialout group? see docs/robot-commands.md)";
    throw ArmctlError(ErrorKind::io, errno_text("open", path, err) + hint);
  }
  auto fail = [&](const char* what) {
    const int err = errno;
    ::close(fd);
    throw ArmctlError(ErrorKind::io, errno_text(what, path, err));
  };
  // A regular file or a FIFO would "work" until the first reply timed out: say what it is.
  if (!::isatty(fd)) {
    ::close(fd);
    throw ArmctlError(ErrorKind::io, path + " is not a serial port or pty (not a tty): name the board's "
                                            "/dev/ttyUSB*, /dev/ttyACM*, /dev/ttyAMA* or a pty");
  }
  // Exclusive: a second armctl (or ModemManager) must not interleave bytes with ours.
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    ::close(fd);
    throw ArmctlError(ErrorKind::io, errno_text("lock", path, err) +
                                         " (another program has the port open)");
  }
  if (::isatty(fd)) {
    if (::ioctl(fd, TIOCEXCL) != 0) fail("set exclusive mode on");
    termios tio{};
    if (::tcgetattr(fd, &tio) != 0) fail("read settings of");
    ::cfmakeraw(&tio);
    tio.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | PARENB | CRTSCTS | CSIZE);
    tio.c_cflag |= CS8 | CLOCAL | CREAD;
    tio.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
    tio.c_cc[VMIN] = 0;
    tio.c_cc[VTIME] = 0;
    if (::cfsetispeed(&tio, *speed) != 0 || ::cfsetospeed(&tio, *speed) != 0) {
      fail("set baud rate of");
    }
    if (::tcsetattr(fd, TCSANOW, &tio) != 0) fail("configure");
    ::tcflush(fd, TCIFLUSH);
  }
  return std::unique_ptr<SerialPort>(new SerialPort(fd, path, baud));
}

SerialPort::SerialPort(int fd, std::string path, std::uint32_t baud)
    : FdStream(fd, std::move(path)), baud_(baud) {}

// TIOCEXCL outlives our descriptor while anyone else keeps the tty open (a pty's keeper):
// clear it so the port can be opened again after we are done.
SerialPort::~SerialPort() {
  if (::isatty(fd())) ::ioctl(fd(), TIOCNXCL);
}

void SerialPort::flush_input() { ::tcflush(fd(), TCIFLUSH); }

}  // namespace armctl::transport
