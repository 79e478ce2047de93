// What the long-running subcommands (sim xarm, sim scara, controller) share: a symlink to their
// pty that lives exactly as long as they do, and the one way armctl handles signals: SIGINT and
// SIGTERM ask a server to stop (its request_stop(): transport::ServeLoop wakes at once), and
// SIGPIPE is ignored (a peer that leaves is an error to handle, not a reason to die).
#pragma once

#include <atomic>
#include <csignal>
#include <filesystem>

namespace armctl::cli {

// Creates `link` -> `target` (replacing an old symlink left by a killed run); removes it on
// destruction. An empty `link` does nothing. Throws ArmctlError(io) naming both paths.
class PtySymlink {
 public:
  PtySymlink(const std::filesystem::path& link, const std::filesystem::path& target);
  ~PtySymlink();
  PtySymlink(const PtySymlink&) = delete;
  PtySymlink& operator=(const PtySymlink&) = delete;

 private:
  std::filesystem::path link_;
};

// While alive, SIGINT and SIGTERM call `server.request_stop()`, which must be
// async-signal-safe (the servers' sets an atomic flag and writes to a pipe; Interrupted's sets
// a flag). Restores the previous handlers on destruction. One at a time per process.
class StopOnSignals {
 public:
  template <typename Server>
  explicit StopOnSignals(Server& server)
      : StopOnSignals([](void* s) { static_cast<Server*>(s)->request_stop(); }, &server) {}
  ~StopOnSignals();
  StopOnSignals(const StopOnSignals&) = delete;
  StopOnSignals& operator=(const StopOnSignals&) = delete;

 private:
  StopOnSignals(void (*stop)(void*), void* context);
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
  struct sigaction old_pipe_ {};
};

// The signal (SIGINT, SIGTERM) that last asked this process to stop, 0 if none: a command
// that fails after one was interrupted by it (main exits 128 + the signal: 130 for Ctrl-C).
int last_stop_signal();

// For a command that loops until Ctrl-C (xarm watch, group run --wait): the flag it checks.
struct Interrupted {
  std::atomic<bool> flag{false};
  void request_stop() { flag = true; }
  explicit operator bool() const { return flag.load(); }
};

}  // namespace armctl::cli
