// What the long-running subcommands (emulate xarm, controller, sim scara --robot-commands)
// share: a symlink to their pty that lives exactly as long as they do, and a clean stop on
// SIGINT/SIGTERM.
#pragma once

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

// While alive, SIGINT and SIGTERM call `stop(context)`, which must be async-signal-safe (the
// runners' request_stop sets an atomic flag and writes to a pipe). Restores the previous
// handlers on destruction. One at a time per process.
class StopOnSignals {
 public:
  StopOnSignals(void (*stop)(void*), void* context);
  ~StopOnSignals();
  StopOnSignals(const StopOnSignals&) = delete;
  StopOnSignals& operator=(const StopOnSignals&) = delete;

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

}  // namespace armctl::cli
