#include "devices/joint_bus/unix_socket.hpp"

#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <fmt/core.h>

#include "core/error.hpp"

namespace armctl::joint_bus::sim_link {

namespace {
sockaddr_un address(const std::string& path) {
  sockaddr_un a{};
  a.sun_family = AF_UNIX;
  if (path.empty() || path.size() >= sizeof(a.sun_path)) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      fmt::format("unix socket path '{}' must be 1..{} characters", path,
                                  sizeof(a.sun_path) - 1));
  }
  std::memcpy(a.sun_path, path.c_str(), path.size() + 1);
  return a;
}

[[noreturn]] void fail(const std::string& what, const std::string& path, int err) {
  throw ArmctlError(ErrorKind::io, fmt::format("{} {}: {} (errno {})", what, path, std::strerror(err), err));
}
}  // namespace

int connect_unix(const std::string& path) {
  const sockaddr_un a = address(path);
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) fail("socket for", path, errno);
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) {
    const int err = errno;
    ::close(fd);
    throw ArmctlError(ErrorKind::io,
                      fmt::format("connect to simulated arm at {}: {} (errno {}); is `armctl sim "
                                  "scara --listen {}` running?",
                                  path, std::strerror(err), err, path));
  }
  return fd;
}

int listen_unix(const std::string& path) {
  const sockaddr_un a = address(path);
  struct stat st{};
  if (::lstat(path.c_str(), &st) == 0) {
    if (!S_ISSOCK(st.st_mode)) {
      throw ArmctlError(ErrorKind::invalid_argument,
                        fmt::format("{} exists and is not a socket: refusing to replace it", path));
    }
    // A socket nobody answers on is left over from a crashed run: replace it.
    const int probe = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    const bool alive = probe >= 0 && ::connect(probe, reinterpret_cast<const sockaddr*>(&a), sizeof a) == 0;
    if (probe >= 0) ::close(probe);
    if (alive) {
      throw ArmctlError(ErrorKind::io, fmt::format("another simulated arm is already listening on {}", path));
    }
    ::unlink(path.c_str());
  }
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) fail("socket for", path, errno);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0 || ::listen(fd, 4) != 0) {
    const int err = errno;
    ::close(fd);
    fail("listen on", path, err);
  }
  return fd;
}

bool send_all(int fd, std::span<const std::uint8_t> bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::send(fd, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    done += static_cast<std::size_t>(n);
  }
  return true;
}

long receive_some(int fd, std::span<std::uint8_t> buffer, TimePoint deadline, const Clock& clock) {
  for (;;) {
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - clock.now()).count();
    pollfd p{fd, POLLIN, 0};
    const int r = ::poll(&p, 1, static_cast<int>(std::clamp<long long>(left, 0, 1 << 30)));
    if (r < 0) {
      if (errno == EINTR) continue;
      return -1;
    }
    if (r == 0) return 0;
    const ssize_t n = ::recv(fd, buffer.data(), buffer.size(), 0);
    if (n > 0) return n;
    if (n < 0 && errno == EINTR) continue;
    return -1;  // 0 = orderly close
  }
}

}  // namespace armctl::joint_bus::sim_link
