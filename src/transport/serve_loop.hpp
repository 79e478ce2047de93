// The one way a long-running server in armctl waits and stops: the emulated xArm on its pty,
// the arm controller on its upstream, the simulated arm on its socket. Each serves in a loop
// of "handle what is ready, then wait()": wait() polls the server's file descriptors until
// one is ready, a timeout passes or a stop is requested, and request_stop() (from any thread
// or a signal handler) wakes it at once through a pipe, so no server sleeps to notice a stop
// and none needs a signal style of its own (apps/armctl/serve_support.hpp: StopOnSignals).
#pragma once

#include <poll.h>

#include <atomic>
#include <optional>
#include <span>

#include "core/clock.hpp"

namespace armctl::transport {

class ServeLoop {
 public:
  ServeLoop();  // throws ArmctlError(io) if the wake pipe cannot be made
  ~ServeLoop();
  ServeLoop(const ServeLoop&) = delete;
  ServeLoop& operator=(const ServeLoop&) = delete;

  // Waits until one of `fds` is ready for its events (their revents are then set), `timeout`
  // has passed (none: no limit; zero: just look), or a stop is requested. Retries after
  // signals. Returns false once a stop was requested. Throws ArmctlError(io) if poll fails.
  bool wait(std::span<pollfd> fds, std::optional<Duration> timeout);

  // Async-signal-safe; callable from any thread, any number of times.
  void request_stop();
  bool stop_requested() const { return stop_.load(); }
  // Serve again after a stop (a runner restarted with start()).
  void clear_stop();

 private:
  int wake_[2] = {-1, -1};
  std::atomic<bool> stop_{false};
};

}  // namespace armctl::transport
