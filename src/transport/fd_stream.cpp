#include "transport/fd_stream.hpp"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include "core/error.hpp"

namespace armctl::transport {

std::string errno_text(const std::string& what, const std::string& path, int err) {
  return what + " " + path + ": " + std::strerror(err) + " (errno " + std::to_string(err) + ")";
}

FdStream::FdStream(int fd, std::string name) : fd_(fd), name_(std::move(name)) {
  const int flags = ::fcntl(fd_, F_GETFL);
  if (flags >= 0 && !(flags & O_NONBLOCK)) ::fcntl(fd_, F_SETFL, flags | O_NONBLOCK);
}

FdStream::~FdStream() {
  if (fd_ >= 0) ::close(fd_);
}

void FdStream::write(std::span<const std::uint8_t> bytes) {
  const TimePoint deadline = clock_.now() + write_timeout_;
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK) {
      throw ArmctlError(ErrorKind::io, errno_text("write to", name_, errno));
    }
    // The output buffer is full: wait until the peer takes some, but not past the deadline.
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - clock_.now()).count();
    if (left <= 0) {
      throw ArmctlError(
          ErrorKind::timeout,
          name_ + ": the peer took " + std::to_string(done) + " of " + std::to_string(bytes.size()) +
              " bytes and then none within " +
              std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(write_timeout_).count()) +
              " ms (is anything reading the other end?)");
    }
    pollfd p{fd_, POLLOUT, 0};
    if (::poll(&p, 1, static_cast<int>(std::min<long long>(left, 1 << 30))) < 0 && errno != EINTR) {
      throw ArmctlError(ErrorKind::io, errno_text("poll", name_, errno));
    }
  }
}

std::size_t FdStream::read(std::span<std::uint8_t> buffer, TimePoint deadline) {
  for (;;) {
    const auto left = deadline - clock_.now();
    const auto ms = std::chrono::ceil<std::chrono::milliseconds>(left).count();
    pollfd p{fd_, POLLIN, 0};
    const int r = ::poll(&p, 1, ms > 0 ? static_cast<int>(std::min<long long>(ms, 1 << 30)) : 0);
    if (r < 0) {
      if (errno == EINTR) continue;
      throw ArmctlError(ErrorKind::io, errno_text("poll", name_, errno));
    }
    if (r == 0) return 0;
    if (p.revents & (POLLIN | POLLHUP | POLLERR)) {
      const ssize_t n = ::read(fd_, buffer.data(), buffer.size());
      if (n > 0) return static_cast<std::size_t>(n);
      if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
      // A pty master reads EIO while no one has the other side open: treat as no data yet.
      if ((n < 0 && errno == EIO) || n == 0) {
        if (clock_.now() >= deadline) return 0;
        pollfd none{-1, 0, 0};
        ::poll(&none, 0, 1);  // avoid spinning while the peer is away
        continue;
      }
      throw ArmctlError(ErrorKind::io, errno_text("read from", name_, errno));
    }
    if (p.revents & POLLNVAL) throw ArmctlError(ErrorKind::io, name_ + ": descriptor is closed");
  }
}

void FdStream::drain() {
  if (::isatty(fd_)) ::tcdrain(fd_);
}

}  // namespace armctl::transport
