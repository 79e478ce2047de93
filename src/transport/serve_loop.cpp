#include "transport/serve_loop.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include <fmt/core.h>

#include "core/error.hpp"

namespace armctl::transport {

ServeLoop::ServeLoop() {
  if (::pipe2(wake_, O_CLOEXEC | O_NONBLOCK) != 0) {
    throw ArmctlError(ErrorKind::io, fmt::format("pipe: {}", std::strerror(errno)));
  }
}

ServeLoop::~ServeLoop() {
  for (int fd : wake_) {
    if (fd >= 0) ::close(fd);
  }
}

void ServeLoop::request_stop() {
  stop_ = true;
  const char byte = 1;
  [[maybe_unused]] ssize_t n = ::write(wake_[1], &byte, 1);  // pipe full: already awake
}

void ServeLoop::clear_stop() {
  stop_ = false;
  char drain[64];
  while (::read(wake_[0], drain, sizeof drain) > 0) {
  }
}

bool ServeLoop::wait(std::span<pollfd> fds, std::optional<Duration> timeout) {
  if (stop_) return false;
  // The caller's descriptors, then the wake pipe.
  pollfd local[8];
  std::vector<pollfd> heap;
  pollfd* all = local;
  if (fds.size() + 1 > std::size(local)) {
    heap.resize(fds.size() + 1);
    all = heap.data();
  }
  for (std::size_t i = 0; i < fds.size(); ++i) all[i] = {fds[i].fd, fds[i].events, 0};
  all[fds.size()] = {wake_[0], POLLIN, 0};

  const SteadyClock clock;
  const std::optional<TimePoint> until =
      timeout ? std::optional<TimePoint>(clock.now() + std::max(Duration::zero(), *timeout)) : std::nullopt;
  for (;;) {
    timespec ts{};
    timespec* ts_ptr = nullptr;
    if (until) {
      const Duration left = std::max(Duration::zero(), *until - clock.now());
      ts.tv_sec = static_cast<time_t>(left.count() / 1'000'000'000);
      ts.tv_nsec = static_cast<long>(left.count() % 1'000'000'000);
      ts_ptr = &ts;
    }
    const int r = ::ppoll(all, fds.size() + 1, ts_ptr, nullptr);
    if (r < 0 && errno == EINTR) {
      if (stop_) return false;
      continue;
    }
    if (r < 0) throw ArmctlError(ErrorKind::io, fmt::format("poll: {}", std::strerror(errno)));
    break;
  }
  for (std::size_t i = 0; i < fds.size(); ++i) fds[i].revents = all[i].revents;
  return !stop_;
}

}  // namespace armctl::transport
